// ffc_shim_contact.cpp: a scene's search, assembly, augmentation, history, statistics, points, multipliers, penalties and rigid motions.
#include "ffc_shim.hpp"

namespace ffc_shim {

// ffcSearch(C, u): contact search of every pair at u; returns the linked points.
long sceneSearch(const Named &, FFScene *const &C, KN<double> *const &u)
{
    const char *fn = "ffcSearch";
    SceneData &d = need_scene(fn, C);
    const double *pu = need_scene_u(fn, d, u);
    need_not_inverted(fn, d, pu);
    long linked = 0, bad = -1;
    int st = ffc_scene_search(d.s, pu, &linked, &bad);
    if (st) scene_error(fn, st, bad, "the search");
    return linked;
}

// the dynamic named arguments v, dt, dvdu of an assembly
basicAC_F0::name_and_type assemble_names[] = {{"tangent", &typeid(string *)},
                                              {"symmetric", &typeid(long)},
                                              {"v", &typeid(KN<double> *)},
                                              {"dt", &typeid(double)},
                                              {"dvdu", &typeid(double)}};

namespace {

// the first pair with friction (mu > 0), -1 when none has
int frictional_pair(const SceneData &d, double *mu = nullptr)
{
    for (int k = 0; k < ffc_scene_npairs(d.s); k++) {
        ffc_pair_opts o;
        ffc_scene_pair_opts(d.s, k, &o);
        if (o.mu > 0) {
            if (mu) *mu = o.mu;
            return k;
        }
    }
    return -1;
}

} // namespace

void scene_motion(const char *fn, const Named &nm, SceneData &d, int iv, int idt, int idvdu)
{
    ffc_effects fx;
    ffc_scene_effects(d.s, &fx);
    const bool given = nm.has(iv) || nm.has(idt) || nm.has(idvdu);
    if (!fx.dynamic) {
        if (given) fail(fn, "arguments 'v', 'dt', 'dvdu': the scene is not dynamic (effects without ffcDynamic)");
        return;
    }
    if (frictional_pair(d) < 0 && !given) return;
    if (!nm.has(iv) || !nm.has(idt) || !nm.has(idvdu))
        fail(fn, "arguments 'v', 'dt', 'dvdu': a dynamic scene with friction needs the velocity at the end of the step, the step and dv/du");
    const double *v = need_scene_u(fn, d, nm.array(iv), "v");
    const double dt = nm.real(idt, 0), dvdu = nm.real(idvdu, 0);
    if (!(dt > 0) || std::isinf(dt)) fail(fn, "argument 'dt': " + num(dt) + " must be finite and > 0 (the time step)");
    if (!(dvdu >= 0) || std::isinf(dvdu))
        fail(fn, "argument 'dvdu': " + num(dvdu) + " must be finite and >= 0 (e.g. gamma / (beta dt) for Newmark)");
    int st = ffc_scene_set_motion(d.s, v, dt, dvdu);
    if (st) scene_error(fn, st, -1, "the motion");
}

namespace {

// ffcAssemble(C, u, R, K, tangent = "consistent", symmetric = 0, [v, dt, dvdu]):
// R = the contact residual at u (size 3 x nodes), K = its tangent
// ("material": without the geometric terms); symmetric = 1 keeps the lower
// triangle (CHOLMOD; frictionless small-strain scenes only). Returns the
// active points. ffcResidual(C, u, R, [v, dt, dvdu]): R alone.
// (iv: the position of the motion options v, dt, dvdu in the call's table)
long sceneAssembleImpl(const char *fn, const Named &nm, FFScene *C, KN<double> *u, KN<double> *R,
                       Matrice_Creuse<double> *K, int iv)
{
    SceneData &d = need_scene(fn, C);
    const double *pu = need_scene_u(fn, d, u);
    need_not_inverted(fn, d, pu);
    need_penalties(fn, d);
    if (!R) fail(fn, "argument 'R': array is not defined");
    const long n = 3 * d.nn;
    int tangent = FFC_TANGENT_NONE;
    bool lower = false;
    if (K) {
        const std::string t = nm.str(AS_TANGENT, "consistent");
        if (t == "consistent") tangent = FFC_TANGENT_CONSISTENT;
        else if (t == "material") tangent = FFC_TANGENT_MATERIAL;
        else fail(fn, "argument 'tangent': \"" + t + "\" is not \"consistent\" or \"material\"");
        const long sym = nm.integer(AS_SYMMETRIC, 0);
        if (sym != 0 && sym != 1) {
            std::ostringstream s;
            s << "argument 'symmetric': " << sym << " must be 0 (full storage) or 1 (lower triangle, CHOLMOD)";
            fail(fn, s.str());
        }
        lower = sym == 1;
        if (lower) {
            ffc_effects fx;
            ffc_scene_effects(d.s, &fx);
            double mu = 0;
            const int k = frictional_pair(d, &mu);
            if (k >= 0) {
                std::ostringstream s;
                s << "argument 'symmetric': 1, but pair " << k << " has friction (mu = " << mu << "): its tangent is not symmetric";
                fail(fn, s.str());
            }
            if (fx.finite_def) fail(fn, "argument 'symmetric': 1, but the scene has finite deformation: its tangent is not symmetric");
        }
    }
    scene_motion(fn, nm, d, iv, iv + 1, iv + 2);
    std::vector<double> Rc(n, 0.0);
    long nt = 0, bad = -1;
    // (buffers sized from the last call's count, left unfilled: one
    // assembly pass where the count holds, a second where it outgrows them)
    std::unique_ptr<long[]> Ti, Tj;
    std::unique_ptr<double[]> Tv;
    int st;
    for (long cap = K ? std::max(d.cLastNt + d.cLastNt / 8 + 1024, 4096L) : 0;;) {
        Ti.reset(new long[cap > 0 ? cap : 1]); Tj.reset(new long[cap > 0 ? cap : 1]); Tv.reset(new double[cap > 0 ? cap : 1]);
        std::fill(Rc.begin(), Rc.end(), 0.0);
        st = ffc_scene_assemble(d.s, pu, tangent, Rc.data(), cap, Ti.get(), Tj.get(), Tv.get(), &nt, &bad);
        if (st != FFC_ERR_CAPACITY) break;
        cap = nt;
    }
    if (K && !st) d.cLastNt = nt;
    if (st) scene_error(fn, st, bad, "the contact assembly");
    R->resize(n);
    for (long i = 0; i < n; i++) (*R)[i] = Rc[i];
    double active = 0;
    ffc_scene_stat(d.s, -1, "active", 0, &active);
    if (!K) return (long)active;
    triplets_to_matrix(fn, n, nt, Ti.get(), Tj.get(), Tv.get(), lower, K);
    return (long)active;
}

} // namespace

long sceneAssemble(const Named &nm, FFScene *const &C, KN<double> *const &u, KN<double> *const &R,
                   Matrice_Creuse<double> *const &K)
{
    if (!K) fail("ffcAssemble", "argument 'K': matrix is not defined");
    return sceneAssembleImpl("ffcAssemble", nm, C, u, R, K, AS_V);
}

long sceneResidual(const Named &nm, FFScene *const &C, KN<double> *const &u, KN<double> *const &R)
{
    return sceneAssembleImpl("ffcResidual", nm, C, u, R, nullptr, 0);
}

// ffcAugment(C, u, [v, dt, dvdu]): Uzawa update of every pair's multipliers;
// returns the active points of the last assembly.
basicAC_F0::name_and_type motion_names[] = {
    {"v", &typeid(KN<double> *)}, {"dt", &typeid(double)}, {"dvdu", &typeid(double)}};

long sceneAugment(const Named &nm, FFScene *const &C, KN<double> *const &u)
{
    const char *fn = "ffcAugment";
    SceneData &d = need_scene(fn, C);
    const double *pu = need_scene_u(fn, d, u);
    need_not_inverted(fn, d, pu);
    need_penalties(fn, d);
    scene_motion(fn, nm, d, 0, 1, 2);
    long bad = -1;
    int st = ffc_scene_augment(d.s, pu, &bad);
    if (st) scene_error(fn, st, bad, "the augmentation");
    double a = 0;
    ffc_scene_stat(d.s, -1, "active", 0, &a);
    return (long)a;
}

// ffcCommit(C, u): u is a converged step (friction history, checkpoint of
// the multipliers); ffcRestore(C): back to that checkpoint (a step cut);
// ffcReset(C): no history, no multipliers.
long sceneCommit(const Named &, FFScene *const &C, KN<double> *const &u)
{
    const char *fn = "ffcCommit";
    SceneData &d = need_scene(fn, C);
    int st = ffc_scene_commit(d.s, need_scene_u(fn, d, u));
    if (st) scene_error(fn, st, -1, "the commit");
    return 0;
}
long sceneRestore(const Named &, FFScene *const &C)
{
    ffc_scene_restore(need_scene("ffcRestore", C).s);
    return 0;
}
long sceneReset(const Named &, FFScene *const &C)
{
    ffc_scene_reset(need_scene("ffcReset", C).s);
    return 0;
}

// ffcStat(C, name, pair = -1, step = 0): a statistic of the last assembly
// (or augmentation) by name, of one pair or of all; step = 1: as it was
// at the last ffcCommit (the converged step).
basicAC_F0::name_and_type pair_only_names[] = {{"pair", &typeid(long)}};
basicAC_F0::name_and_type stat_names[] = {{"pair", &typeid(long)}, {"step", &typeid(long)}};
basicAC_F0::name_and_type points_names[] = {{"pair", &typeid(long)}, {"nodes", &typeid(long)}};

double sceneStat(const Named &nm, FFScene *const &C, string *const &name)
{
    const char *fn = "ffcStat";
    SceneData &d = need_scene(fn, C);
    const int k = need_pair_index(fn, d, nm.integer(0, -1), true);
    const std::string n = name ? *name : "";
    double v = 0;
    const long step = nm.integer(1, 0);
    if (step != 0 && step != 1) {
        std::ostringstream s;
        s << "argument 'step': " << step << " must be 0 (the last assembly) or 1 (the last commit)";
        fail(fn, s.str());
    }
    int st = ffc_scene_stat(d.s, k, n.c_str(), (int)step, &v);
    if (st == FFC_ERR_LABEL) {
        std::ostringstream s;
        s << "argument 'name': \"" << n << "\" is not a statistic; the statistics are:";
        for (int i = 0; ffc_scene_stat_name(i); i++) s << " " << ffc_scene_stat_name(i);
        fail(fn, s.str());
    }
    if (st) scene_error(fn, st, -1, "the statistic");
    return v;
}

// ffcPoints(C, u, P, pair = -1, nodes = 0): one row per slave point
// (augmented Lagrangian: per quadrature point; node-to-surface and mortar,
// or with nodes = 1 every method with nodal multipliers: per slave node;
// columns of ffc_points: x, y, z, gap, pressure, active, area, master
// facet, traction x, y, z, friction state, dissipation); returns the rows.
long scenePoints(const Named &nm, FFScene *const &C, KN<double> *const &u, KNM<double> *const &P)
{
    const char *fn = "ffcPoints";
    SceneData &d = need_scene(fn, C);
    const int k = need_pair_index(fn, d, nm.integer(0, -1), true);
    const long nodes = nm.integer(1, 0);
    if (nodes != 0 && nodes != 1) {
        std::ostringstream s;
        s << "argument 'nodes': " << nodes << " is not 0 (the method's own points) or 1 (the slave nodes)";
        fail(fn, s.str());
    }
    const double *pu = need_scene_u(fn, d, u);
    if (!P) fail(fn, "argument 'P': array is not defined");
    const long n = ffc_scene_npoints(d.s, k, (int)nodes);
    if (n == FFC_ERR_VALUE)
        fail(fn, "argument 'nodes': 1, but a pair of this call has pointwise multipliers (nodal = 0): its values live "
                 "at the quadrature points only");
    if (n < 0) scene_error(fn, (int)n, -1, "the points");
    std::vector<double> rows(n * FFC_POINT_COLS + 1);
    long got = 0, bad = -1;
    int st = ffc_scene_points(d.s, pu, k, (int)nodes, n, rows.data(), &got, &bad);
    if (st) scene_error(fn, st, bad, "the points");
    P->resize(n, FFC_POINT_COLS);
    for (long r = 0; r < n; r++)
        for (long c = 0; c < FFC_POINT_COLS; c++) (*P)(r, c) = rows[r * FFC_POINT_COLS + c];
    return n;
}

namespace {

// ffcMultipliers(C, k, lambda[, lambdaT]): pair k's normal multipliers (one
// per node with nodal multipliers, else one per point) and, when asked, the
// tangential ones (3 each: the traction of the last augmentation); returns
// their count. Both arrays are checked before either is written.
long multipliers_out(FFScene *C, long k, KN<double> *lam, KN<double> *lamT, bool tangential)
{
    const char *fn = "ffcMultipliers";
    SceneData &d = need_scene(fn, C);
    const int p = need_pair_index(fn, d, k, false, "k");
    if (!lam) fail(fn, "argument 'lambda': array is not defined");
    if (tangential && !lamT) fail(fn, "argument 'lambdaT': array is not defined");
    long n = 0;
    ffc_scene_multipliers(d.s, p, 0, nullptr, nullptr, &n);
    std::vector<double> l(n + 1), lt(3 * n + 1);
    ffc_scene_multipliers(d.s, p, n, l.data(), lt.data(), &n);
    lam->resize(n);
    for (long i = 0; i < n; i++) (*lam)[i] = l[i];
    if (tangential) {
        lamT->resize(3 * n);
        for (long i = 0; i < 3 * n; i++) (*lamT)[i] = lt[i];
    }
    return n;
}

} // namespace
long sceneMultipliers(const Named &, FFScene *const &C, long const &k, KN<double> *const &lam)
{
    return multipliers_out(C, k, lam, nullptr, false);
}
long sceneMultipliersT(const Named &, FFScene *const &C, long const &k, KN<double> *const &lam, KN<double> *const &lamT)
{
    return multipliers_out(C, k, lam, lamT, true);
}

// ffcFacetSize(C, pair = -1): the contact mesh size of a pair (or the
// smallest over all): the smaller mean longest facet edge of its two sides.
double sceneFacetSize(const Named &nm, FFScene *const &C)
{
    const char *fn = "ffcFacetSize";
    SceneData &d = need_scene(fn, C);
    const int k = need_pair_index(fn, d, nm.integer(0, -1), true);
    double h = 0;
    int st = ffc_scene_facet_size(d.s, k, &h);
    if (st == FFC_ERR_EMPTY) fail(fn, "argument 'C': the scene has no pair yet (ffcAddPair)");
    if (st) scene_error(fn, st, -1, "the facet size");
    return h;
}

// ffcAutoPenalty(C, k, lame1, lame2): the automatic normal penalty of pair
// k (see ffc_scene_auto_penalty) from Lame's constants per tetrahedron
// (P0 arrays of the scene's mesh: lame1[], lame2[]).
double sceneAutoPenalty(const Named &, FFScene *const &C, long const &k, KN<double> *const &l1, KN<double> *const &l2)
{
    const char *fn = "ffcAutoPenalty";
    SceneData &d = need_scene(fn, C);
    const int p = need_pair_index(fn, d, k, false, "k");
    need_lame(fn, d, l1, l2);
    std::vector<double> Ep[2];
    const std::vector<long> *tets[2] = {&d.tetS[p], &d.tetM[p]};
    for (int side = 0; side < 2; side++)
        for (long t : *tets[side]) {
            const double e = ffc_plane_modulus((*l1)[t], (*l2)[t]);
            if (!(e > 0)) {
                std::ostringstream s;
                s << "tetrahedron " << t << " behind a " << (side ? "master" : "slave") << " facet of pair " << p
                  << " has no material (lame1 = " << num((*l1)[t]) << ", lame2 = " << num((*l2)[t]) << ")";
                fail(fn, s.str());
            }
            Ep[side].push_back(e);
        }
    double eps = 0;
    int st = ffc_scene_auto_penalty(d.s, p, Ep[0].data(), Ep[1].data(), &eps);
    if (st) scene_error(fn, st, -1, "the automatic penalty");
    return eps;
}

// ffcFreeMotions(C, M) and ffcFreeMotions(C, u, M): the rigid motions of
// the scene's bodies that its prescribed dofs (ffcFixed) leave free
// (ffc_scene_free_motions), one row each: body (its lowest node), t x y z,
// w x y z, p x y z, that node's x y z, the amount of u along it (0 without
// u), the body's first tetrahedron; returns the count.
static long free_motions(const char *fn, FFScene *C, KN<double> *u, KNM<double> *M)
{
    SceneData &d = need_scene(fn, C);
    const double *pu = u ? need_scene_u(fn, d, u) : nullptr;
    if (!M) fail(fn, "argument 'M': array is not defined");
    long n = 0;
    int st = ffc_scene_free_motions(d.s, pu, 0, nullptr, &n);
    std::vector<ffc_motion> m(n + 1);
    if (st == FFC_ERR_CAPACITY) st = ffc_scene_free_motions(d.s, pu, n, m.data(), &n);
    if (st == FFC_ERR_EMPTY) fail(fn, "argument 'C': the scene was made without tetrahedra");
    if (st) scene_error(fn, st, -1, "the free rigid motions");
    M->resize(n, FFC_MOTION_COLS);
    for (long r = 0; r < n; r++) {
        (*M)(r, (long)FFC_MO_BODY) = m[r].body;
        for (long k = 0; k < 3; k++) {
            (*M)(r, FFC_MO_T + k) = m[r].t[k];
            (*M)(r, FFC_MO_W + k) = m[r].w[k];
            (*M)(r, FFC_MO_P + k) = m[r].p[k];
            (*M)(r, FFC_MO_X + k) = m[r].x[k];
        }
        (*M)(r, (long)FFC_MO_AMOUNT) = m[r].amount;
        (*M)(r, (long)FFC_MO_TET) = m[r].tet;
    }
    return n;
}
long sceneFreeMotions(const Named &, FFScene *const &C, KNM<double> *const &M)
{
    return free_motions("ffcFreeMotions", C, nullptr, M);
}
long sceneFreeMotionsU(const Named &, FFScene *const &C, KN<double> *const &u, KNM<double> *const &M)
{
    if (!u) fail("ffcFreeMotions", "argument 'u': array is not defined");
    return free_motions("ffcFreeMotions", C, u, M);
}

// ffcInverted(C, u): the first tetrahedron inverted or collapsed at u, -1 if none.
// ffcFixed(C, fixed): the prescribed dofs (fixed[i] != 0, 3 per node: a
// Dirichlet mask; > 0 held at zero, < 0 moved), read by the nodal friction
// law and the free motions (ffc_scene_set_fixed).
long sceneFixed(const Named &, FFScene *const &C, KN<double> *const &fixed)
{
    const char *fn = "ffcFixed";
    SceneData &d = need_scene(fn, C);
    int st = ffc_scene_set_fixed(d.s, need_scene_u(fn, d, fixed, "fixed"));
    if (st) scene_error(fn, st, -1, "the prescribed dofs");
    return 0;
}

long sceneInverted(const Named &, FFScene *const &C, KN<double> *const &u)
{
    const char *fn = "ffcInverted";
    SceneData &d = need_scene(fn, C);
    long bad = -1;
    return ffc_scene_check_volume(d.s, need_scene_u(fn, d, u), &bad) == FFC_ERR_INVERTED ? bad : -1;
}

// ffcSelfPassed(C, u): the points of self pairs that crossed an opposite
// facet of their own surface since the last commit (ffc_scene_self_passed);
// 0 without self pairs.
long sceneSelfPassed(const Named &, FFScene *const &C, KN<double> *const &u)
{
    const char *fn = "ffcSelfPassed";
    SceneData &d = need_scene(fn, C);
    long bad = -1, n = 0;
    int st = ffc_scene_self_passed(d.s, need_scene_u(fn, d, u), &n, &bad);
    if (st) scene_error(fn, st, bad, "the pass-through check");
    return n;
}

// ffcSurfaceDofs(C, mask): mask = 1 on the dofs of every node of the
// pairs' facets (slave and master sides), 0 elsewhere (resized to the
// scene's dofs). Returns the number of such nodes.
long sceneSurfaceDofs(const Named &, FFScene *const &C, KN<double> *const &mask)
{
    const char *fn = "ffcSurfaceDofs";
    SceneData &d = need_scene(fn, C);
    if (!mask) fail(fn, "argument 'mask': array is not defined");
    if (ffc_scene_npairs(d.s) == 0) fail(fn, "argument 'C': the scene has no pair yet (ffcAddPair)");
    std::vector<double> m(3 * d.nn);
    const long count = ffc_scene_surface_mask(d.s, 3 * d.nn, m.data());
    if (count < 0) scene_error(fn, (int)count, -1, "the surface dofs");
    mask->resize(3 * d.nn);
    for (long i = 0; i < 3 * d.nn; i++) (*mask)[i] = m[i];
    return count;
}

} // namespace ffc_shim
