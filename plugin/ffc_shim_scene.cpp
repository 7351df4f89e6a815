// ffc_shim_scene.cpp: the ffcScene type's argument checks and errors, making a scene, its pairs and their options.
#include "ffc_shim.hpp"

namespace ffc_shim {

// ---------------------------------------------------------------------------
// Contact scenes (script type ffcScene): a mesh's nodes and any number of
// contact pairs with their own options, links, multipliers and history,
// kept between calls (ffc_scene_*); options by name, statistics by name.

// The helpers of the scene calls: labels, effects bits, finite arrays.
namespace {

// Slave and master label lists: non-empty, and disjoint (false) or the
// same set (true: self-contact)
bool need_pair_labels(const char *fn, KN<long> *sl, KN<long> *ml)
{
    if (!sl || sl->N() == 0) fail(fn, "argument 'slaveLabs': empty list of labels");
    if (!ml || ml->N() == 0) fail(fn, "argument 'masterLabs': empty list of labels");
    std::set<long> S, M;
    for (long i = 0; i < sl->N(); i++) S.insert((*sl)[i]);
    for (long j = 0; j < ml->N(); j++) M.insert((*ml)[j]);
    if (S == M) return true;
    for (long l : S)
        if (M.count(l)) {
            std::ostringstream s;
            s << "label " << l << " is in both 'slaveLabs' and 'masterLabs' (self-contact takes the same labels on both "
                 "sides; else each label on one side)";
            fail(fn, s.str());
        }
    return false;
}

ffc_effects need_effects(const char *fn, long bits, const char *arg = "argument 'opt': effects = opt[1]")
{
    if (bits < 0 || bits > 3) {
        std::ostringstream s;
        s << arg << " = " << bits << " is not a set of effects (ffcFriction + ffcDynamic: 1 friction, 2 time"
          << (bits >= 4 && bits <= 7 ? "; finite deformation is the bulk's: bulk = \"neohookean\")" : ")");
        fail(fn, s.str());
    }
    ffc_effects e = {(bits & 1) ? 1 : 0, (bits & 2) ? 1 : 0, 0};
    return e;
}

} // namespace

std::string labels_text(const KN<long> &l)
{
    std::ostringstream s;
    s << "{";
    for (long i = 0; i < l.N(); i++) s << (i ? ", " : "") << l[i];
    s << "}";
    return s.str();
}

// every entry of the array x (argument `name`) finite
void need_finite(const char *fn, const char *name, KN<double> *x)
{
    for (long k = 0; k < x->N(); k++)
        if (!std::isfinite((*x)[k])) {
            std::ostringstream s;
            s << "argument '" << name << "': " << name << "[" << k << "] = " << num((*x)[k]) << " is not finite";
            fail(fn, s.str());
        }
}

SceneData &need_scene(const char *fn, FFScene *C)
{
    if (!C || !C->d || !C->d->s)
        fail(fn, "argument 'C': the scene is not made: declare it with ffcScene C(Th) (or ffcScene C(Th, effects = ..., order = 2))");
    return *C->d;
}

// u (argument 'u') of the scene's mesh: 3 values per node, finite, no
// tetrahedron inverted.
const double *need_scene_u(const char *fn, SceneData &d, KN<double> *u, const char *arg)
{
    const std::string a = std::string("argument '") + arg + "': ";
    if (!u) fail(fn, a + "array is not defined");
    if (u->N() != 3 * d.nn) {
        std::ostringstream s;
        s << a << "size " << u->N() << ", expected " << 3 * d.nn << " = 3 x " << d.nn
          << (d.order == 2 ? " P2 nodes" : " vertices") << " of the scene's mesh";
        if (d.order == 2 && u->N() == 3 * d.m.nv)
            s << " (it has the size of a [P1,P1,P1] field: a scene made with order = 2 needs fespace Vh(Th, [P2,P2,P2]))";
        else if (d.order == 1 && d.m.nt > 0 && u->N() > 3 * d.m.nv)
            s << " (a [P2,P2,P2] field needs the scene made with order = 2)";
        else s << " (is it the mesh the scene was made with?)";
        fail(fn, s.str());
    }
    need_finite(fn, arg, u);
    return &(*u)[0];
}

// every pair has its normal penalty
void need_penalties(const char *fn, SceneData &d)
{
    for (int k = 0; k < ffc_scene_npairs(d.s); k++) {
        ffc_pair_opts o;
        ffc_scene_pair_opts(d.s, k, &o);
        if (o.eps_n > 0 || o.method == FFC_METHOD_NTS) continue;
        std::ostringstream s;
        s << "pair " << k << " (" << d.labels[k] << ") has no normal penalty yet: give epsN in ffcAddPair, or set it with "
          << "ffcSetPair(C, " << k << ", epsN = ffcAutoPenalty(C, " << k << ", lame1, lame2)) (solveScene() of scene.idp does that)";
        fail(fn, s.str());
    }
}

void need_not_inverted(const char *fn, SceneData &d, const double *u)
{
    long bad = -1;
    if (ffc_scene_check_volume(d.s, u, &bad) == FFC_ERR_INVERTED) {
        const long *T = d.m.T.data() + 4 * bad;
        std::ostringstream s;
        s << "argument 'u': tetrahedron " << bad << " (vertices " << T[0] << ", " << T[1] << ", " << T[2] << ", "
          << T[3] << ") is inverted or collapsed by the displacement: did Newton diverge? (ffcInverted(C, u) tests this)";
        fail(fn, s.str());
    }
}

[[noreturn]] void scene_error(const char *fn, int st, long bad, const char *what)
{
    std::ostringstream s;
    s << what << ": " << ffc_strerror(st);
    if (bad >= 0) s << " (at " << bad << ")";
    if (st == FFC_ERR_DEGENERATE) s << ": an inverted or collapsed facet; did Newton diverge?";
    fail(fn, s.str());
}

// the pair index k (argument arg) of the scene; -1 allowed when all is set
int need_pair_index(const char *fn, const SceneData &d, long k, bool all, const char *arg)
{
    const long np = ffc_scene_npairs(d.s);
    if ((all && k == -1) || (k >= 0 && k < np)) return (int)k;
    std::ostringstream s;
    s << "argument '" << arg << "': " << k << " is not a pair of the scene (" << np << " pair" << (np == 1 ? "" : "s")
      << ": 0.." << np - 1 << (all ? ", or -1 for all" : "") << ")";
    fail(fn, s.str());
}

// Lame's constants lame1, lame2 per tetrahedron of the scene's mesh (P0
// arrays): defined, one value per tetrahedron, finite.
void need_lame(const char *fn, const SceneData &d, KN<double> *l1, KN<double> *l2)
{
    const char *arg[2] = {"lame1", "lame2"};
    KN<double> *l[2] = {l1, l2};
    for (int i = 0; i < 2; i++) {
        if (!l[i]) fail(fn, std::string("argument '") + arg[i] + "': array is not defined");
        if (l[i]->N() != d.m.nt) {
            std::ostringstream s;
            s << "argument '" << arg[i] << "': size " << l[i]->N() << ", expected " << d.m.nt
              << " (one value per tetrahedron: the coefficients of a P0 function)";
            fail(fn, s.str());
        }
        need_finite(fn, arg[i], l[i]);
    }
}

// ffcScene C(Th, effects = 0, order = 1, engine = "auto", shareLinks = 1, bulk = "elastic", bulkLinear = 0,
// bulkSymmetric = 1, bulkFinite = 0)
basicAC_F0::name_and_type scene_names[] = {
    {"effects", &typeid(long)},       {"order", &typeid(long)},         {"engine", &typeid(string *)},
    {"shareLinks", &typeid(long)},    {"bulk", &typeid(string *)},      {"bulkLinear", &typeid(long)},
    {"bulkSymmetric", &typeid(long)}, {"bulkFinite", &typeid(long)}};

// a bulk law's name, as ffcScene's argument bulk gives it
const char *bulk_name(ffc_bulk_kind kind)
{
    static const char *const name[] = {"elastic", "neohookean", "user", "svk", "mooneyrivlin"};
    return kind >= FFC_BULK_LINEAR && kind <= FFC_BULK_MOONEYRIVLIN ? name[kind] : "?";
}

namespace {

// The bulk law the arguments bulk, bulkLinear, bulkSymmetric, bulkFinite
// (arguments 4..7) declare: a built-in law is what it is (its flags may
// not be given); the user's declares its own.
ffc_bulk_law need_law(const char *fn, const Named &nm)
{
    const std::string kind = nm.str(4, "elastic");
    ffc_bulk_law law;
    if (kind == "elastic") law = ffc_bulk_law_of(FFC_BULK_LINEAR);
    else if (kind == "neohookean") law = ffc_bulk_law_of(FFC_BULK_NEOHOOKEAN);
    else if (kind == "svk") law = ffc_bulk_law_of(FFC_BULK_SVK);
    else if (kind == "mooneyrivlin") law = ffc_bulk_law_of(FFC_BULK_MOONEYRIVLIN);
    else if (kind == "user") law = ffc_bulk_law_of(FFC_BULK_USER);
    else fail(fn, "argument 'bulk': \"" + kind + "\" is not \"elastic\", \"neohookean\", \"svk\", \"mooneyrivlin\" or \"user\"");
    const char *flag[3] = {"bulkLinear", "bulkSymmetric", "bulkFinite"};
    int *val[3] = {&law.linear, &law.symmetric, &law.finite};
    for (int k = 0; k < 3; k++) {
        if (!nm.has(5 + k)) continue;
        if (law.kind != FFC_BULK_USER)
            fail(fn, std::string("argument '") + flag[k] + "': only a bulk = \"user\" declares what it is (\"" + kind +
                         "\" is " + (law.linear ? "linear, " : "nonlinear, ") + "symmetric, " +
                         (law.finite ? "finite deformation" : "small strain") + ")");
        const long v = nm.integer(5 + k, 0);
        if (v != 0 && v != 1) fail(fn, std::string("argument '") + flag[k] + "': " + std::to_string(v) + " is not 0 or 1");
        *val[k] = (int)v;
    }
    if (law.linear && law.finite) fail(fn, "arguments 'bulkLinear' and 'bulkFinite': a bulk of finite deformation is not linear");
    return law;
}

} // namespace

FFScene *sceneInit(const Named &nm, FFScene *const &C, pmesh3 const &pTh)
{
    const char *fn = "ffcScene";
    const Mesh3 &Th = need_mesh(fn, pTh);
    const long bits = nm.integer(0, 0), order = nm.integer(1, 1);
    ffc_effects fx = need_effects(fn, bits, "argument 'effects'");
    if (order != 1 && order != 2) {
        std::ostringstream s;
        s << "argument 'order': " << order << " is not 1 ([P1,P1,P1] displacement) or 2 ([P2,P2,P2])";
        fail(fn, s.str());
    }
    const std::string engine = nm.str(2, "auto");
    if (engine != "auto" && engine != "replicated" && engine != "mumps")
        fail(fn, "argument 'engine': '" + engine + "' is not \"auto\", \"replicated\" or \"mumps\"");
    const long share = nm.integer(3, 1);
    if (share != 0 && share != 1) {
        std::ostringstream s;
        s << "argument 'shareLinks': " << share << " is not 1 (several ranks: each evaluates its share of the contact "
          << "links) or 0 (every rank evaluates every link)";
        fail(fn, s.str());
    }
    std::unique_ptr<SceneData> d(new SceneData);
    mesh_arrays(Th, d->m);
    if (d->m.nbe == 0) fail(fn, "argument 'Th': the mesh has no boundary faces");
    d->face = face_map(d->m);
    d->order = (int)order;
    const double *X = d->m.X.data();
    std::vector<long> T = d->m.T;
    d->nn = d->m.nv;
    if (order == 2) {
        p2_arrays(fn, d->m, d->p2);
        d->nn = d->p2.nn;
        X = d->p2.X2.data();
        for (long k = 0; k < d->m.nt; k++)
            for (int a = 0; a < 4; a++) T[4 * k + a] = d->p2.node[10 * k + a];
    }
    const ffc_bulk_law law = need_law(fn, nm);
    int st = ffc_scene_create(order == 2 ? 6 : 3, d->nn, X, d->m.nt, T.data(), &fx, &d->s);
    if (st) scene_error(fn, st, -1, "the scene");
    st = ffc_scene_set_law(d->s, &law);
    if (st) scene_error(fn, st, -1, "the scene's bulk");
    // several ranks (FreeFem++-mpi): the bulk factorized by CHOLMOD on every rank with the compliance
    // columns shared out ("auto", "replicated"), or by parallel MUMPS ("mumps")
    int rank, ranks, fcomm;
    ffc_mpi_world(&rank, &ranks, &fcomm);
    if (ranks > 1) {
        const ffc_parallel par = {engine == "mumps" ? FFC_ENGINE_MUMPS : FFC_ENGINE_REPLICATED, fcomm, 0, (int)share};
        st = ffc_scene_set_parallel(d->s, &par);
        if (st) scene_error(fn, st, -1, "the scene's parallel engine");
    }
    if (C->d) C->destroy();
    C->d = d.release();
    return C;
}

// The label list of a pair's side (argument arg): one label or an int[int].
KN<long> side_labels(const char *fn, const char *arg, KN<long> *l)
{
    if (!l) fail(fn, std::string("argument '") + arg + "': array is not defined");
    if (l->N() == 0) fail(fn, std::string("argument '") + arg + "': empty list of labels");
    return *l;
}

// The pair options of the named arguments (from o, the current ones).
basicAC_F0::name_and_type pair_names[] = {
    {"method", &typeid(string *)}, {"mu", &typeid(double)},   {"epsN", &typeid(double)}, {"epsT", &typeid(double)},
    {"qdeg", &typeid(long)},       {"nodal", &typeid(long)},  {"crel", &typeid(double)}, {"cabs", &typeid(double)},
    {"muD", &typeid(double)},      {"gtol", &typeid(double)}, {"ftol", &typeid(double)}, {"maxFlips", &typeid(long)},
    {"scale", &typeid(double)},    {"dual", &typeid(long)},   {"dualT", &typeid(long)}};

namespace {

const char *method_name(int m) { return m == FFC_METHOD_NTS ? "nts" : m == FFC_METHOD_MORTAR ? "mortar" : "al"; }

} // namespace

ffc_pair_opts named_pair_opts(const char *fn, const Named &nm, const SceneData &d, ffc_pair_opts o)
{
    // a pair added without a method: the first pair's, or for the first
    // the augmented Lagrangian, named once (measured per kind of scene,
    // tests/bench/README.md: the one method that runs every kind)
    std::string def = method_name(o.method);
    if (fn == std::string("ffcAddPair") && !nm.has(PO_METHOD)) {
        if (ffc_scene_npairs(d.s) > 0) {
            ffc_pair_opts o0;
            ffc_scene_pair_opts(d.s, 0, &o0);
            def = method_name(o0.method);
        } else {
            int rank;
            ffc_mpi_world(&rank, nullptr, nullptr);
            if (rank == 0)
                std::cout << "ffcAddPair: method \"al\" (augmented Lagrangian), the default: it runs every kind of "
                             "scene; method = \"nts\" or \"mortar\" names another (README: Which method to choose)"
                          << std::endl;
        }
    }
    const std::string method = nm.str(PO_METHOD, def);
    if (method != "al" && method != "nts" && method != "mortar") {
        std::ostringstream s;
        s << "argument 'method': \"" << method << "\" is not a method of scenes (\"al\": augmented Lagrangian, \"nts\": "
             "node-to-surface, \"mortar\": segment-to-segment)";
        fail(fn, s.str());
    }
    const int m = method == "nts" ? FFC_METHOD_NTS : method == "mortar" ? FFC_METHOD_MORTAR : FFC_METHOD_AL;
    if (m == FFC_METHOD_NTS && d.order != 1)
        fail(fn, "argument 'method': \"" + method + "\" takes linear facets only: a scene of order 1 ([P1,P1,P1])");
    // a new mortar pair integrates each segment triangle with the rule of degree 2 on linear facets, 3 on
    // quadratic ones (exact for the products of the displacements' and the multipliers' shape functions
    // that its small-strain integrals on flat facets are)
    if (m == FFC_METHOD_MORTAR && o.method != FFC_METHOD_MORTAR && !nm.has(PO_QDEG)) o.qdeg = d.order == 2 ? 3 : 2;
    if (fn == std::string("ffcSetPair")) {
        if (m != o.method) fail(fn, "argument 'method': a pair keeps the method it was added with");
    } else if (ffc_scene_npairs(d.s) > 0) {
        ffc_pair_opts o0;
        ffc_scene_pair_opts(d.s, 0, &o0);
        if (o0.method != m)
            fail(fn, "argument 'method': \"" + method + "\", but pair 0 uses \"" + method_name(o0.method) +
                         "\": the pairs of a scene share one method");
    }
    o.method = m;
    o.mu_d = nm.real(PO_MUD, o.mu_d);
    o.gtol = nm.real(PO_GTOL, o.gtol);
    o.ftol = nm.real(PO_FTOL, o.ftol);
    o.max_flips = (int)nm.integer(PO_FLIPS, o.max_flips);
    o.scale = nm.real(PO_SCALE, o.scale);
    o.mu = nm.real(PO_MU, o.mu);
    o.eps_n = nm.real(PO_EPSN, o.eps_n);
    o.eps_t = nm.real(PO_EPST, o.eps_t);
    o.qdeg = (int)nm.integer(PO_QDEG, o.qdeg);
    o.nodal = (int)nm.integer(PO_NODAL, o.nodal);
    o.dual = (int)nm.integer(PO_DUAL, o.dual);
    o.dual_t = (int)nm.integer(PO_DUALT, o.dual_t);
    o.search.capture_rel = nm.real(PO_CREL, o.search.capture_rel);
    o.search.capture_abs = nm.real(PO_CABS, o.search.capture_abs);
    auto bad = [&](int i, double v, const char *why) {
        std::ostringstream s;
        s << "argument '" << nm.name(i) << "': " << num(v) << " " << why;
        fail(fn, s.str());
    };
    if (!(o.mu >= 0) || std::isinf(o.mu)) bad(PO_MU, o.mu, "must be finite and >= 0 (Coulomb coefficient)");
    if (o.mu > 0) {
        ffc_effects fx;
        ffc_scene_effects(d.s, &fx);
        if (!fx.friction) {   // (the fix keeps the scene's other effects and its bulk)
            std::string e = "ffcFriction";
            if (fx.dynamic) e += " + ffcDynamic";
            ffc_bulk_law law;
            ffc_scene_law(d.s, &law);
            if (law.kind != FFC_BULK_LINEAR) e += std::string(", bulk = \"") + bulk_name(law.kind) + "\"";
            bad(PO_MU, o.mu, ("> 0, but the scene's effects have no friction: make it with ffcScene C(Th, effects = " + e + ")").c_str());
        }
    }
    if (nm.has(PO_EPSN) && (!(o.eps_n > 0) || std::isinf(o.eps_n))) bad(PO_EPSN, o.eps_n, "must be finite and > 0 (normal penalty)");
    if (!(o.eps_t >= 0) || std::isinf(o.eps_t)) bad(PO_EPST, o.eps_t, "must be finite and >= 0 (tangential penalty; 0: epsN)");
    if (ffc_quad_size(o.qdeg) < 0) bad(PO_QDEG, o.qdeg, "is not a quadrature degree (1..6)");
    if (o.nodal != 0 && o.nodal != 1) bad(PO_NODAL, o.nodal, "must be 1 (multipliers at slave nodes) or 0 (at quadrature points)");
    if (m == FFC_METHOD_MORTAR && o.nodal != 1) bad(PO_NODAL, o.nodal, "must be 1 with method \"mortar\" (its multipliers live at the slave nodes)");
    if (o.dual != 0 && o.dual != 1) bad(PO_DUAL, o.dual, "must be 1 (dual multipliers) or 0 (standard)");
    if (o.dual_t != 0 && o.dual_t != 1) bad(PO_DUALT, o.dual_t, "must be 1 (friction sums in the dual basis) or 0 (standard)");
    if (o.dual_t && (m != FFC_METHOD_AL || o.nodal != 1 || d.order != 1))
        bad(PO_DUALT, o.dual_t, "needs method \"al\" with nodal = 1 on linear facets (a scene of order 1): the nodal law's friction sums");
    if (!(o.search.capture_rel >= 0) || std::isinf(o.search.capture_rel)) bad(PO_CREL, o.search.capture_rel, "must be finite and >= 0");
    if (!(o.search.capture_abs >= 0) || std::isinf(o.search.capture_abs)) bad(PO_CABS, o.search.capture_abs, "must be finite and >= 0");
    if (std::isnan(o.mu_d) || std::isinf(o.mu_d) || o.mu_d > o.mu)
        bad(PO_MUD, o.mu_d, "must be finite and <= mu (dynamic friction coefficient; < 0: mu)");
    if (!(o.gtol >= 0) || std::isinf(o.gtol)) bad(PO_GTOL, o.gtol, "must be finite and >= 0 (gap tolerance; 0: 1e-11 x the facet size)");
    if (!(o.ftol >= 0) || std::isinf(o.ftol)) bad(PO_FTOL, o.ftol, "must be finite and >= 0 (tension release tolerance)");
    if (o.max_flips < 1) bad(PO_FLIPS, o.max_flips, "must be >= 1");
    if (!(o.scale >= 0) || std::isinf(o.scale)) bad(PO_SCALE, o.scale, "must be finite and >= 0 (row scale; 0: from the bulk matrix)");
    return o;
}

// The facets of the labels labs (argument arg), from the mesh as the scene
// was made: F (nodes per facet: the scene's order), tet the tetrahedron
// behind each; returns their count.
long select_facets(const char *fn, const SceneData &d, const char *arg, const KN<long> &labs, std::vector<long> &F,
                   std::vector<long> &tet)
{
    std::vector<long> L(labs.N()), out(3 * d.m.nbe);
    for (long i = 0; i < labs.N(); i++) L[i] = labs[i];
    long bad = -1;
    int st = ffc_surface_select(3, d.m.nbe, d.m.be.data(), d.m.belab.data(), d.m.beopp.data(), d.m.nv, d.m.X.data(),
                                (int)L.size(), L.data(), d.m.nbe, out.data(), &bad);
    if (st < 0) {
        std::ostringstream s;
        if (st == FFC_ERR_LABEL)
            s << "argument '" << arg << "': no boundary face carries label " << bad << "; labels present: " << labels_present(d.m);
        else
            s << "argument '" << arg << "': " << ffc_strerror(st) << " (face " << bad << ")";
        fail(fn, s.str());
    }
    tet.resize(st);
    for (long f = 0; f < (long)st; f++) tet[f] = d.m.betet[face_of(d.face, &out[3 * f])];
    if (d.order == 2) {
        F.resize(6 * (long)st);
        p2_facets(fn, d.m, d.p2, d.face, st, out.data(), F.data());
    } else
        F.assign(out.begin(), out.begin() + 3 * (long)st);
    return (long)st;
}

// ffcAddPair(C, slaveLabs, masterLabs, method = "al", mu = 0, epsN, epsT = 0,
// qdeg = 4, nodal = 1, crel = 2, cabs = 0): returns the pair's index.
long addPair(const Named &nm, FFScene *const &C, KN<long> *const &sl, KN<long> *const &ml)
{
    const char *fn = "ffcAddPair";
    SceneData &d = need_scene(fn, C);
    KN<long> S = side_labels(fn, "slaveLabs", sl), M = side_labels(fn, "masterLabs", ml);
    const bool self = need_pair_labels(fn, &S, &M);
    ffc_pair_opts o = named_pair_opts(fn, nm, d, ffc_pair_defaults());
    if (self && o.method == FFC_METHOD_NTS)
        fail(fn, std::string("argument 'method': \"") + method_name(o.method) + "\": self-contact (the same labels " +
                     labels_text(S) + " on both sides) takes method \"al\" or \"mortar\"");
    o.search.self = self;
    auto select = [&](const char *arg, const KN<long> &labs, std::vector<long> &F, std::vector<long> &tet) {
        return select_facets(fn, d, arg, labs, F, tet);
    };
    std::vector<long> Fs, Fm, tS, tM;
    long nfs, nfm;
    if (self) { // self-contact: the facets label by label in the order given (the search links two facing
                // facets from the one listed first), the same list on both sides
        nfs = 0;
        std::set<long> done;
        for (long i = 0; i < S.N(); i++) {
            if (!done.insert(S[i]).second) continue;   // (a label given twice)
            KN<long> one(1);
            one[0] = S[i];
            std::vector<long> F1, t1;
            nfs += select("slaveLabs", one, F1, t1);
            Fs.insert(Fs.end(), F1.begin(), F1.end());
            tS.insert(tS.end(), t1.begin(), t1.end());
        }
        Fm = Fs;
        tM = tS;
        nfm = nfs;
    } else {
        nfs = select("slaveLabs", S, Fs, tS);
        nfm = select("masterLabs", M, Fm, tM);
    }
    long bad = -1;
    const int k = ffc_scene_add_pair(d.s, nfs, Fs.data(), nfm, Fm.data(), &o, &bad);
    if (k == FFC_ERR_FUSED) {
        std::ostringstream s;
        s << "slave facet " << bad << " (labels " << labels_text(S) << ") lies on nodes of the master surface (labels "
          << labels_text(M) << "): the two bodies share their nodes there, meshed as one; contact needs separate nodes "
          << "on each side (in gmsh: no BooleanFragments or Coherence between bodies in contact, no merged points)";
        fail(fn, s.str());
    }
    if (k == FFC_ERR_INTERIOR) {
        const bool sl = bad < nfs;
        std::ostringstream s;
        s << "argument '" << (sl ? "slaveLabs" : "masterLabs") << "': facet " << (sl ? bad : bad - nfs) << " (labels "
          << labels_text(sl ? S : M) << ") lies inside the mesh, with tetrahedra on both sides: the bodies there are "
          << "meshed as one and share their nodes, so they can neither separate nor press on each other; contact needs "
          << "separate nodes on each side (in gmsh: no BooleanFragments or Coherence between bodies in contact, no "
          << "merged points)";
        fail(fn, s.str());
    }
    if (k < 0) scene_error(fn, k, bad, "the pair");
    d.labels.push_back("slave " + labels_text(S) + " / master " + labels_text(M));
    d.tetS.push_back(tS);
    d.tetM.push_back(tM);
    return k;
}

long addPairL(const Named &nm, FFScene *const &C, long const &s, long const &m)
{
    KN<long> S(1), M(1);
    S[0] = s;
    M[0] = m;
    return addPair(nm, C, &S, &M);
}

// a label on one side, an int[int] of labels on the other
long addPairLA(const Named &nm, FFScene *const &C, long const &s, KN<long> *const &M)
{
    KN<long> S(1);
    S[0] = s;
    return addPair(nm, C, &S, M);
}
long addPairAL(const Named &nm, FFScene *const &C, KN<long> *const &S, long const &m)
{
    KN<long> M(1);
    M[0] = m;
    return addPair(nm, C, S, &M);
}

// ffcError(fn, what): stops the script with "fn: what" (an ExecError), for
// the scene library's own argument checks
long ffcErrorCall(string *const &fn, string *const &what)
{
    fail(fn ? *fn : std::string("?"), what ? *what : std::string());
}

// ffcSetPair(C, k, mu = ..., epsN = ..., ...): changes pair k's options; returns k.
long setPair(const Named &nm, FFScene *const &C, long const &k)
{
    const char *fn = "ffcSetPair";
    SceneData &d = need_scene(fn, C);
    const int p = need_pair_index(fn, d, k, false, "k");
    ffc_pair_opts o;
    ffc_scene_pair_opts(d.s, p, &o);
    o = named_pair_opts(fn, nm, d, o);
    int st = ffc_scene_set_pair_opts(d.s, p, &o);
    if (st) scene_error(fn, st, -1, "the pair's options");
    return k;
}

// ffcOption(C, k, name): pair k's option name ("mu", "epsN", "epsT", "qdeg",
// "nodal", "crel", "cabs").
double pairOption(const Named &, FFScene *const &C, long const &k, string *const &name)
{
    const char *fn = "ffcOption";
    SceneData &d = need_scene(fn, C);
    const int p = need_pair_index(fn, d, k, false, "k");
    ffc_pair_opts o;
    ffc_scene_pair_opts(d.s, p, &o);
    const std::string n = name ? *name : "";
    if (n == "mu") return o.mu;
    if (n == "epsN") return o.eps_n;
    if (n == "epsT") return o.eps_t;
    if (n == "qdeg") return o.qdeg;
    if (n == "nodal") return o.nodal;
    if (n == "crel") return o.search.capture_rel;
    if (n == "cabs") return o.search.capture_abs;
    if (n == "nts") return o.method == FFC_METHOD_NTS;
    if (n == "mortar") return o.method == FFC_METHOD_MORTAR;
    if (n == "self") return o.search.self;
    if (n == "obstacle") {
        ffc_obstacle ob;
        return ffc_scene_obstacle(d.s, p, &ob) == FFC_OK;
    }
    if (n == "dual") return o.dual;
    if (n == "dualT") return o.dual_t;
    if (n == "muD") return o.mu_d;
    if (n == "gtol") return o.gtol;
    if (n == "ftol") return o.ftol;
    if (n == "maxFlips") return o.max_flips;
    if (n == "scale") return o.scale;
    if (n == "method")
        fail(fn, "argument 'name': \"method\" is a string and ffcOption returns numbers: read it as ffcOption(C, k, \"nts\") "
                 "(1: node-to-surface) and ffcOption(C, k, \"mortar\") (1: mortar), both 0 for the augmented Lagrangian");
    fail(fn, "argument 'name': \"" + n + "\" is not an option of a pair (mu, epsN, epsT, qdeg, nodal, crel, cabs, nts, mortar, self, obstacle, dual, dualT, muD, gtol, "
                "ftol, maxFlips, scale)");
}

long nPairs(const Named &, FFScene *const &C) { return ffc_scene_npairs(need_scene("ffcPairs", C).s); }

// ffcEffects(C): the scene's effects as bits (1 friction, 2 dynamic, 4 finite deformation)
long sceneEffects(const Named &, FFScene *const &C)
{
    ffc_effects fx;
    ffc_scene_effects(need_scene("ffcEffects", C).s, &fx);
    return fx.friction + 2L * fx.dynamic + 4L * fx.finite_def;
}

} // namespace ffc_shim
