// ffcontact.cpp: FreeFEM shim of the ffcontact C kernels (converts meshes and arrays to plain C arrays, calls C, turns status codes into ExecError): the registration of its calls and of the type ffcScene.
#include "ffc_shim.hpp"

using namespace ffc_shim;

namespace {

void init_scene()
{
    Dcl_Type<FFScene *>(InitP<FFScene>, Destroy<FFScene>);
    zzzfff->Add("ffcScene", atype<FFScene *>());
    typedef FFScene *S;
    typedef KN<double> *V;
    TheOperators->Add("<-", named<S, S, pmesh3>("ffcScene", scene_names, 8, sceneInit));
    Global.Add("ffcAddPair", "(", named<long, S, KN<long> *, KN<long> *>("ffcAddPair", pair_names, PO_N, addPair));
    Global.Add("ffcAddPair", "(", named<long, S, long, long>("ffcAddPair", pair_names, PO_N, addPairL));
    Global.Add("ffcAddPair", "(", named<long, S, long, KN<long> *>("ffcAddPair", pair_names, PO_N, addPairLA));
    Global.Add("ffcAddPair", "(", named<long, S, KN<long> *, long>("ffcAddPair", pair_names, PO_N, addPairAL));
    init_obstacle_names();
    Global.Add("ffcAddObstacle", "(", named<long, S, KN<long> *, string *>("ffcAddObstacle", obstacle_names, OB_N, addObstacle));
    Global.Add("ffcAddObstacle", "(", named<long, S, long, string *>("ffcAddObstacle", obstacle_names, OB_N, addObstacleL));
    Global.Add("ffcMoveObstacle", "(", named<long, S, long>("ffcMoveObstacle", obstacle_names, OB_N, moveObstacle));
    Global.Add("ffcObstaclesAt", "(", named<long, S, double>("ffcObstaclesAt", nullptr, 0, obstaclesAt));
    Global.Add("ffcObstacle", "(", named<double, S, long, string *>("ffcObstacle", nullptr, 0, obstacleValue));
    Global.Add("ffcError", "(", new OneOperator2_<long, string *, string *>(ffcErrorCall));
    Global.Add("ffcSetPair", "(", named<long, S, long>("ffcSetPair", pair_names, PO_N, setPair));
    Global.Add("ffcOption", "(", named<double, S, long, string *>("ffcOption", nullptr, 0, pairOption));
    Global.Add("ffcPairs", "(", named<long, S>("ffcPairs", nullptr, 0, nPairs));
    Global.Add("ffcEffects", "(", named<long, S>("ffcEffects", nullptr, 0, sceneEffects));
    Global.Add("ffcSearch", "(", named<long, S, V>("ffcSearch", nullptr, 0, sceneSearch));
    Global.Add("ffcAssemble", "(",
               named<long, S, V, V, Matrice_Creuse<double> *>("ffcAssemble", assemble_names, AS_N, sceneAssemble));
    Global.Add("ffcResidual", "(", named<long, S, V, V>("ffcResidual", motion_names, 3, sceneResidual));
    Global.Add("ffcAugment", "(", named<long, S, V>("ffcAugment", motion_names, 3, sceneAugment));
    Global.Add("ffcCommit", "(", named<long, S, V>("ffcCommit", nullptr, 0, sceneCommit));
    Global.Add("ffcRestore", "(", named<long, S>("ffcRestore", nullptr, 0, sceneRestore));
    Global.Add("ffcReset", "(", named<long, S>("ffcReset", nullptr, 0, sceneReset));
    Global.Add("ffcStat", "(", named<double, S, string *>("ffcStat", stat_names, 2, sceneStat));
    Global.Add("ffcPoints", "(", named<long, S, V, KNM<double> *>("ffcPoints", points_names, 2, scenePoints));
    Global.Add("ffcMultipliers", "(", named<long, S, long, V>("ffcMultipliers", nullptr, 0, sceneMultipliers));
    Global.Add("ffcMultipliers", "(", named<long, S, long, V, V>("ffcMultipliers", nullptr, 0, sceneMultipliersT));
    Global.Add("ffcInverted", "(", named<long, S, V>("ffcInverted", nullptr, 0, sceneInverted));
    Global.Add("ffcSelfPassed", "(", named<long, S, V>("ffcSelfPassed", nullptr, 0, sceneSelfPassed));
    Global.Add("ffcFixed", "(", named<long, S, V>("ffcFixed", nullptr, 0, sceneFixed));
    Global.Add("ffcSurfaceDofs", "(", named<long, S, V>("ffcSurfaceDofs", nullptr, 0, sceneSurfaceDofs));
    Global.Add("ffcAutoPenalty", "(", named<double, S, long, V, V>("ffcAutoPenalty", nullptr, 0, sceneAutoPenalty));
    Global.Add("ffcFreeMotions", "(", named<long, S, KNM<double> *>("ffcFreeMotions", nullptr, 0, sceneFreeMotions));
    Global.Add("ffcFreeMotions", "(", named<long, S, V, KNM<double> *>("ffcFreeMotions", nullptr, 0, sceneFreeMotionsU));
    Global.Add("ffcFacetSize", "(", named<double, S>("ffcFacetSize", pair_only_names, 1, sceneFacetSize));
    typedef Matrice_Creuse<double> *M;
    Global.Add("ffcBulk", "(", named<long, S, M>("ffcBulk", bulk_names, 1, sceneBulk));
    Global.Add("ffcElastic", "(", named<long, S, M, V, V>("ffcElastic", nullptr, 0, sceneElastic));
    Global.Add("ffcHyperForce", "(", named<double, S, V, V, V, V>("ffcHyperForce", hyper_names, 1, sceneHyperForce));
    Global.Add("ffcHyperTangent", "(", named<long, S, V, V, V, M>("ffcHyperTangent", hyper_names, 1, sceneHyperTangent));
    Global.Add("ffcSolve", "(", named<long, S, M, V, V>("ffcSolve", nullptr, 0, sceneSolve));
    Global.Add("ffcFullSolve", "(", named<long, S, M, V, V>("ffcFullSolve", full_names, 4, sceneFullSolve));
    Global.Add("ffcSolveMessage", "(", named<string *, S>("ffcSolveMessage", nullptr, 0, sceneSolveMessage));
    Global.Add("ffcNTSSolve", "(", named<long, S, V, V, V, V, V>("ffcNTSSolve", nullptr, 0, sceneNTSSolve));
    Global.Add("ffcNewton", "(", named<long, S, V, V, V>("ffcNewton", newton_names, 11, sceneNewton));
    Global.Add("ffcSolverStat", "(", named<double, S, string *>("ffcSolverStat", nullptr, 0, sceneSolverStat));
    Global.Add("ffcNTSStep", "(", named<long, S>("ffcNTSStep", nullptr, 0, sceneNtsStep));
    Global.Add("ffcRows", "(", named<long, S, V, V, M, M, M, V>("ffcRows", nullptr, 0, sceneRows));
    Global.Add("ffcUpdate", "(", named<long, S, V, V>("ffcUpdate", nullptr, 0, sceneUpdate));
    Global.Add("ffcNTSForce", "(", named<long, S, V>("ffcNTSForce", nullptr, 0, sceneNtsForce));
    register_driver();
}

} // namespace

static void init()
{
    init_scene();
    Global.Add("ffcSurface", "(",
               new OneOperator3_<long, pmesh3, KN<long> *, KN<long> *>(ffcSurface));
    Global.Add("ffcArea", "(",
               new OneOperator3_<double, pmesh3, KN<long> *, KN<double> *>(ffcArea));
    Global.Add("ffcTime", "(", new OneOperator0<double>(ffcTime));
    Global.Add("ffcRank", "(", new OneOperator0<long>(ffcRank));
    Global.Add("ffcParallelSolve", "(", new OneOperator3_<long, Matrice_Creuse<double> *, KN<double> *, KN<double> *>(parallelSolve));
    Global.Add("ffcRanks", "(", new OneOperator0<long>(ffcRanks));
    Global.Add("ffcBarrier", "(", new OneOperator0<long>(ffcBarrier));
    Global.Add("ffcPeakMB", "(", new OneOperator0<double>(ffcPeakMB));
    Global.Add("ffcRankSum", "(", new OneOperator1<double, double>(ffcRankSum));
    Global.Add("ffcRankMax", "(", new OneOperator1<double, double>(ffcRankMax));
    Global.Add("ffcRankSum", "(", new OneOperator1_<long, KN<double> *>(ffcRankSumArray));
    Global.Add("ffcRankSum", "(", new OneOperator1_<long, Matrice_Creuse<double> *>(ffcRankSumMatrix));
    Global.Add("ffcParallelSolve", "(", new OneOperator4_<long, Matrice_Creuse<double> *, KN<double> *, KN<double> *, long>(parallelSolveOwn));
    Global.Add("ffcMassSpread", "(",
               new OneOperator4_<long, Matrice_Creuse<double> *, KN<double> *, KNM<double> *, Matrice_Creuse<double> *>(massSpread));
    Global.Add("ffcInverted", "(", new OneOperator2_<long, pmesh3, KN<double> *>(ffcInverted));
    Global.Add("ffcMeshQuality", "(", new OneOperator1_<double, pmesh3>(ffcMeshQuality));
    Global.Add("ffcMeshQuality", "(", new OneOperator2_<long, pmesh3, double>(ffcMeshQualityBelow));
    Global.Add("ffcP2Nodes", "(", new OneOperator2_<long, pmesh3, KN<double> *>(ffcP2Nodes));
    Global.Add("ffcSaveVTK", "(", new OneOperator2_<long, string *, KNM<double> *>(ffcSaveVTK));
    Global.Add("ffcWriteColumns", "(",
               new OneOperator4_<long, string *, string *, KNM<double> *, KN<double> *>(ffcWriteColumns));
    Global.Add("ffcNormals", "(",
               new OneOperator4_<long, pmesh3, KN<long> *, KN<double> *, KN<double> *>(ffcNormals));
}

LOADFUNC(init)
