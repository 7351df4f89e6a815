// ffc_shim.hpp: the declarations the files of the FreeFEM shim share (mesh arrays, checks, matrix conversions, named arguments, ffcScene, the calls).
#ifndef FFC_SHIM_HPP
#define FFC_SHIM_HPP

#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <algorithm>
#include <cstring>
#include <array>
#include <chrono>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "ffc.h"
#include <memory>

using namespace Fem2D;

namespace ffc_shim {

// Plain-array view of a tetrahedral mesh and its boundary faces.
struct MeshArrays {
    long nv = 0, nbe = 0;
    std::vector<double> X;     // [nv*3] vertex coordinates
    std::vector<long> be;      // [nbe*3] boundary face vertices
    std::vector<long> belab;   // [nbe] boundary face labels
    std::vector<long> beopp;   // [nbe] vertex of the adjacent tet opposite the face
    long nt = 0;
    std::vector<long> T;       // [nt*4] tetrahedra
    std::vector<long> betet;   // [nbe] tetrahedron behind each boundary face
};

// Quadratic (P2) nodes: FreeFEM's scalar P2 numbering, rebuilt from the mesh.
// (declared before use in need_pair)
struct P2Arrays {
    long nn = 0;               // nodes
    std::vector<long> node;    // [nt*10] nodes of each tetrahedron
    std::vector<double> X2;    // [nn*3] positions (vertices, edge midpoints)
    std::vector<long> vnode;   // [nv] node of each vertex
};

// The boundary face of each (sorted) vertex triple.
typedef std::map<std::array<long, 3>, long> FaceMap;

// ---------------------------------------------------------------------------
// Meshes, arguments, matrices (ffc_shim_mesh.cpp)

void mesh_arrays(const Mesh3 &Th, MeshArrays &m);
[[noreturn]] void fail(const std::string &fn, const std::string &what);
std::string labels_present(const MeshArrays &m);
void p2_arrays(const char *fn, const MeshArrays &m, P2Arrays &p);
FaceMap face_map(const MeshArrays &m);
long face_of(const FaceMap &face, const long v[3]);
void p2_facets(const char *fn, const MeshArrays &m, const P2Arrays &p2, const FaceMap &face, long nf, const long *F3,
               long *out6);
std::string num(double v);
const char *bulk_name(ffc_bulk_kind kind); // "elastic", "neohookean", "user", "svk", "mooneyrivlin"
const Mesh3 &need_mesh(const char *fn, pmesh3 pTh);
long matrix_triplets(const char *fn, const char *arg, Matrice_Creuse<double> *K, std::vector<long> &Ti,
                     std::vector<long> &Tj, std::vector<double> &Tv);
void set_matrix(long n, long nk, long *Ci, long *Cj, double *Cv, bool lower, Matrice_Creuse<double> *K);
void triplets_to_matrix(const char *fn, long n, long nt, const long *Ti, const long *Tj, const double *Tv, bool lower,
                        Matrice_Creuse<double> *K, const char *what = "the contact tangent");

// the calls of ffc_shim_mesh.cpp
long ffcSurface(pmesh3 const &pTh, KN<long> *const &labs, KN<long> *const &F);
long ffcP2Nodes(pmesh3 const &pTh, KN<double> *const &X2);
double ffcArea(pmesh3 const &pTh, KN<long> *const &F, KN<double> *const &u);
long ffcNormals(pmesh3 const &pTh, KN<long> *const &F, KN<double> *const &u,
                KN<double> *const &N);
long ffcSaveVTK(string *const &file, KNM<double> *const &P);
long ffcWriteColumns(string *const &file, string *const &header, KNM<double> *const &A,
                     KN<double> *const &mask);
long ffcInverted(pmesh3 const &pTh, KN<double> *const &u);
double ffcMeshQuality(pmesh3 const &pTh);
long ffcMeshQualityBelow(pmesh3 const &pTh, double const &q);
double ffcTime();
long ffcRank();
long ffcRanks();
double ffcRankSum(double x);
long ffcRankSumArray(KN<double> *const &v);
long ffcRankSumMatrix(Matrice_Creuse<double> *const &A);
double ffcRankMax(double x);
long ffcBarrier();
double ffcPeakMB();

// ---------------------------------------------------------------------------
// Named arguments and the scenes' data

// Named arguments of a call, each evaluated on demand (absent: the default).
struct Named {
    const basicAC_F0::name_and_type *names;
    const Expression *e;
    Stack s;
    const char *fn;
    bool has(int i) const { return e[i] != nullptr; }
    double real(int i, double def) const { return e[i] ? GetAny<double>((*e[i])(s)) : def; }
    long integer(int i, long def) const { return e[i] ? GetAny<long>((*e[i])(s)) : def; }
    std::string str(int i, const std::string &def) const
    {
        if (!e[i]) return def;
        string *p = GetAny<string *>((*e[i])(s));
        return p ? *p : def;
    }
    KN<double> *array(int i) const { return e[i] ? GetAny<KN<double> *>((*e[i])(s)) : nullptr; }
    const Expression (*vec)[3];   // the entries of a named [x, y, z] (a name of type E_Array)
    // a named [x, y, z] into v; false when not named
    bool vec3(int i, double v[3]) const
    {
        if (!e[i]) return false;
        for (int k = 0; k < 3; k++) v[k] = GetAny<double>((*vec[i][k])(s));
        return true;
    }
    const char *name(int i) const { return names[i].name; }
};

const int MAXNAMED = 48;

// A script type's name in words (for messages).
inline std::string type_word(aType t)
{
    if (t == atype<double>()) return "real";
    if (t == atype<long>()) return "int";
    if (t == atype<bool>()) return "bool";
    if (t == atype<string *>()) return "string";
    if (t == atype<KN<double> *>()) return "real[int]";
    if (t == atype<E_Array>()) return "[x, y, z]";
    if (t == atype<KN<long> *>()) return "int[int]";
    return t->name();
}

// A FreeFEM operator with positional arguments A... and the named ones of
// a table (as FreeFEM's own plugins declare them): f(named, positional...).
template <class R, class... A>
class NamedOp : public OneOperator {
public:
    typedef R (*func)(const Named &, const A &...);

private:
    func f;
    const char *fn;
    basicAC_F0::name_and_type *names;
    int nn;
    class Code : public E_F0mps {
    public:
        func f;
        const char *fn;
        basicAC_F0::name_and_type *names;
        Expression a[sizeof...(A)];
        Expression nargs[MAXNAMED];
        Expression vec[MAXNAMED][3];   // the entries of a named [x, y, z]
        Code(func ff, const char *fname, basicAC_F0::name_and_type *nm, int n, const basicAC_F0 &args,
             const Expression *e)
            : f(ff), fn(fname), names(nm)
        {
            for (size_t i = 0; i < sizeof...(A); i++) a[i] = e[i];
            for (int i = 0; i < MAXNAMED; i++) nargs[i] = nullptr;
            args.SetNameParam(n, names, nargs);
            for (int i = 0; i < n; i++) {
                if (!nargs[i] || *names[i].type != typeid(E_Array)) continue;
                const E_Array *v = dynamic_cast<const E_Array *>(nargs[i]);
                if (!v || v->size() != 3) {
                    std::ostringstream s;
                    s << fname << ": option '" << names[i].name << "' takes 3 values [x, y, z]" << (v ? ", not " : "");
                    if (v) s << v->size();
                    CompileError(s.str());
                }
                for (int k = 0; k < 3; k++) vec[i][k] = to<double>((*v)[k]);
            }
        }
        template <size_t... I>
        AnyType call(Stack s, std::index_sequence<I...>) const
        {
            Named nm{names, nargs, s, fn, vec};
            return SetAny<R>(f(nm, GetAny<A>((*a[I])(s))...));
        }
        AnyType operator()(Stack s) const { return call(s, std::index_sequence_for<A...>()); }
    };

public:
    NamedOp(const char *fname, basicAC_F0::name_and_type *nm, int n, func ff)
        : OneOperator(map_type[typeid(R).name()], ArrayOfaType(map_type[typeid(A).name()]..., false)), f(ff),
          fn(fname), names(nm), nn(n)
    {
    }
    E_F0 *code(const basicAC_F0 &args) const
    {
        // an unknown option, or one of the wrong type, named in the message
        if (args.named_parameter)
            for (const auto &kv : *args.named_parameter) {
                int i = 0;
                while (i < nn && strcmp(kv.first, names[i].name)) i++;
                std::ostringstream s;
                s << fn << ": ";
                if (i == nn) {
                    s << "unknown option '" << kv.first << "'; the options are:";
                    for (int j = 0; j < nn; j++) s << " " << names[j].name;
                    if (!nn) s << " none";
                    CompileError(s.str());
                }
                const aType want = map_type[names[i].type->name()];
                if (!want->CastingFrom(kv.second.left())) {
                    s << "option '" << kv.first << "' takes a " << type_word(want) << " value";
                    if (want == atype<E_Array>()) s << " (its values written out: from an array c, [c[0], c[1], c[2]])";
                    CompileError(s.str());
                }
            }
        Expression e[sizeof...(A)];
        for (size_t i = 0; i < sizeof...(A); i++) e[i] = t[i]->CastTo(args[i]);
        return new Code(f, fn, names, nn, args, e);
    }
};

// The operator of f for the registration: named fn, with the named arguments names[n].
template <class R, class... A>
NamedOp<R, A...> *named(const char *fn, basicAC_F0::name_and_type *names, int n, R (*f)(const Named &, const A &...))
{
    return new NamedOp<R, A...>(fn, names, n, f);
}

// What a scene keeps besides the C scene: the mesh's arrays (labels and
// faces for new pairs), its P2 numbering, and each pair's labels.
struct SceneData {
    ffc_scene *s = nullptr;
    MeshArrays m;
    FaceMap face;           // boundary face of each vertex triple
    P2Arrays p2;
    int order = 1;          // 1: [P1,P1,P1], 2: [P2,P2,P2]
    long nn = 0;            // nodes: vertices or P2 nodes
    std::vector<std::string> labels; // per pair: "slave {..} / master {..}"
    std::vector<std::vector<long>> tetS, tetM; // per pair: the tetrahedron behind each slave / master facet
    ffc_newton_info newton{};  // the last ffcNewton
    std::vector<double> ntsM;  // ffcNTSSolve's multipliers, kept at the largest row count met (one call per solve)
    ffc_full *full = nullptr;  // ffcFullSolve's solver (its analysed pattern)
    std::string iterativeKey;  // the settings its iterative path was last set from (ffcFullSolve)
    std::string solveMessage;  // why its last solve failed, in the engine's words ("" when it solved)
    // the hyperelastic bulk (ffcHyperForce, ffcHyperTangent): its node graph
    // (ffc_tets_pattern: rp[nn + 1], adj[nb]) and the tangent's rows and
    // columns (9 nb), made at the first call
    std::vector<long> hrp, hadj, hKi, hKj;
    std::vector<double> hKv;
    // the contact tangent's last count of triplets (ffcAssemble sizes its
    // buffers from it: one assembly pass a call where the count holds)
    long cLastNt = 0;
    ~SceneData()
    {
        ffc_full_free(full);
        ffc_scene_free(s);
    }
};

} // namespace ffc_shim

// The script type: a pointer to SceneData, set by ffcScene C(Th, ...).
struct FFScene {
    ffc_shim::SceneData *d;
    void init() { d = nullptr; }
    void destroy()
    {
        delete d;
        d = nullptr;
    }
};

namespace ffc_shim {

// ---------------------------------------------------------------------------
// The scenes' checks and errors (ffc_shim_scene.cpp, scene_motion: ffc_shim_contact.cpp)

void need_finite(const char *fn, const char *name, KN<double> *x);
SceneData &need_scene(const char *fn, FFScene *C);
// the driver layers' calls and constants (ffc_shim_driver.cpp)
void register_driver();
const double *need_scene_u(const char *fn, SceneData &d, KN<double> *u, const char *arg = "u");
void need_penalties(const char *fn, SceneData &d);
void need_not_inverted(const char *fn, SceneData &d, const double *u);
[[noreturn]] void scene_error(const char *fn, int st, long bad, const char *what);
int need_pair_index(const char *fn, const SceneData &d, long k, bool all, const char *arg = "pair");
void need_lame(const char *fn, const SceneData &d, KN<double> *l1, KN<double> *l2);
void scene_motion(const char *fn, const Named &nm, SceneData &d, int iv, int idt, int idvdu);

// The named arguments of the calls: the pair options (ffcAddPair,
// ffcSetPair) and those of an assembly (ffcAssemble), by position.
enum { PO_METHOD, PO_MU, PO_EPSN, PO_EPST, PO_QDEG, PO_NODAL, PO_CREL, PO_CABS, PO_MUD, PO_GTOL, PO_FTOL, PO_FLIPS,
       PO_SCALE, PO_DUAL, PO_DUALT, PO_N };
// a pair's options from the named arguments (indices PO_*), from o (ffcAddPair, ffcSetPair, ffcAddObstacle)
ffc_pair_opts named_pair_opts(const char *fn, const Named &nm, const SceneData &d, ffc_pair_opts o);
// the facets of labels labs (argument arg) and the tetrahedron behind each; their count
long select_facets(const char *fn, const SceneData &d, const char *arg, const KN<long> &labs, std::vector<long> &F,
                   std::vector<long> &tet);
enum { AS_TANGENT, AS_SYMMETRIC, AS_V, AS_DT, AS_DVDU, AS_N };
extern basicAC_F0::name_and_type scene_names[], pair_names[], assemble_names[], motion_names[], pair_only_names[],
    stat_names[], points_names[], bulk_names[], newton_names[], full_names[], hyper_names[];

// the calls of ffc_shim_scene.cpp
FFScene *sceneInit(const Named &nm, FFScene *const &C, pmesh3 const &pTh);
long addPair(const Named &nm, FFScene *const &C, KN<long> *const &sl, KN<long> *const &ml);
long sceneSelfPassed(const Named &, FFScene *const &C, KN<double> *const &u);
// a label list as text: {1, 2}
std::string labels_text(const KN<long> &l);
// the label list of a pair's side (argument arg): defined, not empty
KN<long> side_labels(const char *fn, const char *arg, KN<long> *l);
// ffc_shim_obstacle.cpp: the named arguments of its calls, the pair options then the obstacle's own
enum { OB_CENTER = PO_N, OB_RADIUS, OB_AXIS, OB_NORMAL, OB_INSIDE, OB_MOVE, OB_N };
extern basicAC_F0::name_and_type obstacle_names[];
void init_obstacle_names();
long addObstacle(const Named &nm, FFScene *const &C, KN<long> *const &sl, string *const &shape);
long addObstacleL(const Named &nm, FFScene *const &C, long const &s, string *const &shape);
long moveObstacle(const Named &nm, FFScene *const &C, long const &k);
long obstaclesAt(const Named &, FFScene *const &C, double const &lf);
double obstacleValue(const Named &, FFScene *const &C, long const &k, string *const &what);
long addPairL(const Named &nm, FFScene *const &C, long const &s, long const &m);
long addPairLA(const Named &nm, FFScene *const &C, long const &s, KN<long> *const &M);
long addPairAL(const Named &nm, FFScene *const &C, KN<long> *const &S, long const &m);
long ffcErrorCall(string *const &fn, string *const &what);
long setPair(const Named &nm, FFScene *const &C, long const &k);
double pairOption(const Named &, FFScene *const &C, long const &k, string *const &name);
long nPairs(const Named &, FFScene *const &C);
long sceneEffects(const Named &, FFScene *const &C);

// the calls of ffc_shim_contact.cpp
long sceneSearch(const Named &, FFScene *const &C, KN<double> *const &u);
long sceneAssemble(const Named &nm, FFScene *const &C, KN<double> *const &u, KN<double> *const &R,
                   Matrice_Creuse<double> *const &K);
long sceneResidual(const Named &nm, FFScene *const &C, KN<double> *const &u, KN<double> *const &R);
long sceneAugment(const Named &nm, FFScene *const &C, KN<double> *const &u);
long sceneCommit(const Named &, FFScene *const &C, KN<double> *const &u);
long sceneRestore(const Named &, FFScene *const &C);
long sceneReset(const Named &, FFScene *const &C);
double sceneStat(const Named &nm, FFScene *const &C, string *const &name);
long scenePoints(const Named &nm, FFScene *const &C, KN<double> *const &u, KNM<double> *const &P);
long sceneMultipliers(const Named &, FFScene *const &C, long const &k, KN<double> *const &lam);
long sceneMultipliersT(const Named &, FFScene *const &C, long const &k, KN<double> *const &lam, KN<double> *const &lamT);
double sceneFacetSize(const Named &nm, FFScene *const &C);
double sceneAutoPenalty(const Named &, FFScene *const &C, long const &k, KN<double> *const &l1, KN<double> *const &l2);
long sceneFreeMotions(const Named &, FFScene *const &C, KNM<double> *const &M);
long sceneFreeMotionsU(const Named &, FFScene *const &C, KN<double> *const &u, KNM<double> *const &M);
long sceneFixed(const Named &, FFScene *const &C, KN<double> *const &fixed);
long sceneInverted(const Named &, FFScene *const &C, KN<double> *const &u);
long sceneSurfaceDofs(const Named &, FFScene *const &C, KN<double> *const &mask);

// the calls of ffc_shim_solve.cpp
long massSpread(Matrice_Creuse<double> *const &M, KN<double> *const &spread, KNM<double> *const &X,
                Matrice_Creuse<double> *const &T);
double sceneHyperForce(const Named &, FFScene *const &C, KN<double> *const &u, KN<double> *const &l1, KN<double> *const &l2,
                       KN<double> *const &f);
long sceneHyperTangent(const Named &, FFScene *const &C, KN<double> *const &u, KN<double> *const &l1, KN<double> *const &l2,
                       Matrice_Creuse<double> *const &K);
long sceneElastic(const Named &, FFScene *const &C, Matrice_Creuse<double> *const &K, KN<double> *const &l1,
                  KN<double> *const &l2);
long sceneBulk(const Named &nm, FFScene *const &C, Matrice_Creuse<double> *const &K);
long sceneSolve(const Named &, FFScene *const &C, Matrice_Creuse<double> *const &Kc, KN<double> *const &b,
                KN<double> *const &x);
long sceneNewton(const Named &nm, FFScene *const &C, KN<double> *const &r, KN<double> *const &u,
                 KN<double> *const &hist);
double sceneSolverStat(const Named &, FFScene *const &C, string *const &name);
long parallelSolve(Matrice_Creuse<double> *const &A, KN<double> *const &b, KN<double> *const &x);
long sceneFullSolve(const Named &, FFScene *const &C, Matrice_Creuse<double> *const &A, KN<double> *const &b,
                    KN<double> *const &x);
string *sceneSolveMessage(const Named &, FFScene *const &C);
long parallelSolveOwn(Matrice_Creuse<double> *const &A, KN<double> *const &b, KN<double> *const &x, const long &own);
long sceneNtsStep(const Named &, FFScene *const &C);
long sceneRows(const Named &, FFScene *const &C, KN<double> *const &u, KN<double> *const &fixed,
               Matrice_Creuse<double> *const &B, Matrice_Creuse<double> *const &Bf, Matrice_Creuse<double> *const &Cm,
               KN<double> *const &cv);
long sceneNTSSolve(const Named &, FFScene *const &C, KN<double> *const &u, KN<double> *const &fixed,
                   KN<double> *const &f, KN<double> *const &x, KN<double> *const &m);
long sceneUpdate(const Named &, FFScene *const &C, KN<double> *const &u, KN<double> *const &m);
long sceneNtsForce(const Named &, FFScene *const &C, KN<double> *const &R);

} // namespace ffc_shim

#endif
