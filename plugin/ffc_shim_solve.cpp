// ffc_shim_solve.cpp: a scene's bulk stiffness and solves (condensed Newton, node-to-surface), parallel solves, mass redistribution.
#include "ffc_shim.hpp"

namespace ffc_shim {

namespace {

// A bulk call's failure: the engine's own reason where it has one (out of
// memory with the sizes it failed on), else the status's text
[[noreturn]] void bulk_error(const char *fn, SceneData &d, int st, long bad, const char *what)
{
    ffc_error e;
    if (ffc_scene_solve_error(d.s, &e) == FFC_OK && e.status == st && e.msg[0])
        fail(fn, std::string(what) + ": " + e.msg);
    scene_error(fn, st, bad, what);
}

} // namespace


// ffcMassSpread(M, spread, X, T): the interpolation T of the redistributed
// mass T' M T (ffc_mass_spread) of a vector space [Pk, Pk, Pk] (dof i of
// component i % 3): the dofs with spread[i] != 0 move with their
// neighbours in M off that set, by weights that reproduce the rigid
// motions at the dofs' positions X (a row per dof: x, y, z; X with no
// row: the mean by |M_ij|). Returns the spread dofs whose row does not reproduce them
// (kept their own row, or too few neighbours off the set).
long massSpread(Matrice_Creuse<double> *const &M, KN<double> *const &spread, KNM<double> *const &X,
                Matrice_Creuse<double> *const &T)
{
    const char *fn = "ffcMassSpread";
    std::vector<long> Mi, Mj;
    std::vector<double> Mv;
    const long n = matrix_triplets(fn, "M", M, Mi, Mj, Mv);
    if (!spread) fail(fn, "argument 'spread': array is not defined");
    if (spread->N() != n) {
        std::ostringstream s;
        s << "argument 'spread': size " << spread->N() << ", expected " << n << " (the rows of M)";
        fail(fn, s.str());
    }
    need_finite(fn, "spread", spread);
    if (!X) fail(fn, "argument 'X': array is not defined");
    if (n % 3) {
        std::ostringstream s;
        s << "argument 'M': " << n << " rows, not a vector space's (3 per node)";
        fail(fn, s.str());
    }
    if (X->N() != 0 && (X->N() != n || X->M() != 3)) {
        std::ostringstream s;
        s << "argument 'X': " << X->N() << " x " << X->M() << ", expected " << n << " x 3 (a row per row of M) or no row";
        fail(fn, s.str());
    }
    std::vector<double> pos(X->N() ? 3 * n : 0);
    for (long i = 0; i < (long)pos.size() / 3; i++)
        for (int c = 0; c < 3; c++) {
            pos[3 * i + c] = (*X)((int)i, c);
            if (!std::isfinite(pos[3 * i + c])) fail(fn, "argument 'X': a non-finite entry");
        }
    if (!T) fail(fn, "argument 'T': matrix is not defined");
    for (size_t k = 0; k < Mv.size(); k++)
        if (!std::isfinite(Mv[k])) fail(fn, "argument 'M': a non-finite entry");
    const long nm = (long)Mv.size();
    const double *x = pos.empty() ? nullptr : pos.data();
    std::vector<long> comp(n);
    for (long i = 0; i < n; i++) comp[i] = i % 3;
    long cap = n + nm, nt = 0, kept = 0, inexact = 0;
    std::vector<long> Ti, Tj;
    std::vector<double> Tv;
    int st = FFC_ERR_CAPACITY;
    for (int pass = 0; pass < 2 && st == FFC_ERR_CAPACITY; pass++) {
        Ti.resize(cap);
        Tj.resize(cap);
        Tv.resize(cap);
        st = ffc_mass_spread(n, nm, Mi.data(), Mj.data(), Mv.data(), x, comp.data(), &(*spread)[0], cap, Ti.data(), Tj.data(),
                             Tv.data(), &nt, &kept, &inexact);
        cap = nt;
    }
    if (st) fail(fn, std::string("the interpolation: ") + ffc_strerror(st));
    triplets_to_matrix(fn, n, nt, Ti.data(), Tj.data(), Tv.data(), false, T);
    return kept + inexact;
}

// ffcBulk(C, K, maxContactDofs = 4000): the scene keeps the bulk stiffness K
// (small strain; Dirichlet rows with FreeFEM's tgv) for ffcSolve, which
// factorizes it once (CHOLMOD, in C) at its first call. Returns the dofs.
basicAC_F0::name_and_type bulk_names[] = {{"maxContactDofs", &typeid(long)}};

// ffcElastic(C, K, lame1, lame2): K = the stiffness of isotropic linear
// elasticity on the scene's mesh, [P1,P1,P1] or, in a scene of order 2,
// [P2,P2,P2] (ffc_elastic_p1, ffc_elastic_p2: what the varf
// int3d(Th)(lame1 div u div v + 2 lame2 eps(u) : eps(v))  gives,
// assembled in C), with Lame's constants per tetrahedron (P0 arrays of
// the scene's mesh). Returns the matrix's entries.
long sceneElastic(const Named &, FFScene *const &C, Matrice_Creuse<double> *const &K, KN<double> *const &l1,
                  KN<double> *const &l2)
{
    const char *fn = "ffcElastic";
    SceneData &d = need_scene(fn, C);
    if (!K) fail(fn, "argument 'K': matrix is not defined");
    need_lame(fn, d, l1, l2);
    std::vector<double> lam(d.m.nt), mu(d.m.nt);
    for (long t = 0; t < d.m.nt; t++) { lam[t] = (*l1)[t]; mu[t] = (*l2)[t]; }
    long nnz = 0, bad = -1;
    int st = FFC_OK;
    std::vector<long> Ki, Kj;
    std::vector<double> Kv;
    for (int pass = 0; pass < 2; pass++) {   // (the count, then the entries)
        const long cap = pass ? nnz : 0;
        if (pass) { Ki.resize(nnz); Kj.resize(nnz); Kv.resize(nnz); }
        const int s2 = d.order == 2
            ? ffc_elastic_p2(d.m.nv, d.m.X.data(), d.m.nt, d.m.T.data(), d.nn, d.p2.node.data(), lam.data(), mu.data(),
                             cap, Ki.data(), Kj.data(), Kv.data(), &nnz, &bad)
            : ffc_elastic_p1(d.m.nv, d.m.X.data(), d.m.nt, d.m.T.data(), lam.data(), mu.data(), cap, Ki.data(),
                             Kj.data(), Kv.data(), &nnz, &bad);
        if (s2 != FFC_ERR_CAPACITY || pass) { st = s2; break; }
    }
    if (st == FFC_ERR_DEGENERATE) {
        std::ostringstream s;
        s << "argument 'C': tetrahedron " << bad << " of the scene's mesh has no volume";
        fail(fn, s.str());
    }
    if (st) scene_error(fn, st, bad, "the elastic stiffness");
    set_matrix(3 * d.nn, nnz, Ki.data(), Kj.data(), Kv.data(), false, K);
    return nnz;
}

// The scene's hyperelastic bulk (bulk = "neohookean", "svk" or
// "mooneyrivlin"; ffc_hyper_assemble on [P1,P1,P1] or [P2,P2,P2]), at the
// displacement u (3 dofs per node), with Lame's constants per tetrahedron
// (P0 arrays) and, for Mooney-Rivlin, its c01 (named argument, P0 array):
//   ffcHyperForce(C, u, lame1, lame2, f, c01 = c): f = its internal force
//     int P : grad v (no loads, no Dirichlet rows); returns the stored energy int W;
//   ffcHyperTangent(C, u, lame1, lame2, K, c01 = c): K = the force's
//     derivative (both triangles); returns its entries.
// The node graph is made once per scene.
namespace {
int hyper_law(const char *fn, SceneData &d)
{
    ffc_bulk_law l;
    ffc_scene_law(d.s, &l);
    if (l.kind == FFC_BULK_NEOHOOKEAN) return FFC_HYPER_NEOHOOKEAN;
    if (l.kind == FFC_BULK_SVK) return FFC_HYPER_SVK;
    if (l.kind == FFC_BULK_MOONEYRIVLIN) return FFC_HYPER_MOONEYRIVLIN;
    fail(fn, "argument 'C': the scene's bulk is not hyperelastic (made with bulk = \"neohookean\", \"svk\" or \"mooneyrivlin\")");
}
ffc_tets hyper_mesh(SceneData &d)
{
    return ffc_tets{d.m.nv, d.m.X.data(), d.m.nt, d.m.T.data(), d.order == 2 ? 10 : 4, d.nn,
                    d.order == 2 ? d.p2.node.data() : d.m.T.data()};
}
// the arguments u, lame1, lame2 checked; the node graph made at the first call
void hyper_prepare(const char *fn, SceneData &d, KN<double> *u, KN<double> *l1, KN<double> *l2)
{
    if (!u) fail(fn, "argument 'u': array is not defined");
    if (u->N() != 3 * d.nn) {
        std::ostringstream s;
        s << "argument 'u': size " << u->N() << ", expected " << 3 * d.nn << " (3 dofs per node of the scene's displacement space)";
        fail(fn, s.str());
    }
    need_finite(fn, "u", u);
    need_lame(fn, d, l1, l2);
    if (!d.hrp.empty()) return;
    const ffc_tets m = hyper_mesh(d);
    std::vector<long> rp(d.nn + 1), adj;
    long nb = 0;
    ffc_error err;
    int st = ffc_tets_pattern(&m, 0, rp.data(), nullptr, &nb, &err);
    if (st == FFC_ERR_CAPACITY) {
        adj.resize(nb);
        st = ffc_tets_pattern(&m, nb, rp.data(), adj.data(), &nb, &err);
    }
    if (st) fail(fn, std::string("the node graph: ") + err.msg);
    d.hKi.resize(9 * nb); d.hKj.resize(9 * nb); d.hKv.resize(9 * nb);
    ffc_tets_pattern_ij(d.nn, rp.data(), adj.data(), d.hKi.data(), d.hKj.data());
    d.hrp.swap(rp);
    d.hadj.swap(adj);
}
// an error of ffc_hyper_assemble, named by the argument it comes from
[[noreturn]] void hyper_fail(const char *fn, const ffc_error &err)
{
    const char *arg = err.status == FFC_ERR_INVERTED || err.where == FFC_AT_DOF ? "u"
                      : err.status == FFC_ERR_VALUE && err.where == FFC_AT_ELEMENT    ? "c01"
                      : err.status == FFC_ERR_NONFINITE && err.where == FFC_AT_ELEMENT ? "lame1, lame2, c01" : "C";
    fail(fn, std::string("argument '") + arg + "': " + err.msg);
}

// the operator at u (its law, the arguments checked, the node graph made
// at the first call): W and f as ffc_hyper_assemble takes them, the
// tangent into d.hKv when asked
void hyper_assemble(const char *fn, const Named &nm, SceneData &d, KN<double> *u, KN<double> *l1, KN<double> *l2,
                    double *W, double f[], bool tangent)
{
    const int law = hyper_law(fn, d);
    hyper_prepare(fn, d, u, l1, l2);
    KN<double> *c = nm.array(0);
    if (law == FFC_HYPER_MOONEYRIVLIN && !c)
        fail(fn, "argument 'c01': a Mooney-Rivlin bulk needs its c01 per tetrahedron (c01 = array)");
    if (law != FFC_HYPER_MOONEYRIVLIN && nm.has(0)) fail(fn, "argument 'c01': only a Mooney-Rivlin bulk takes it");
    if (c && c->N() != d.m.nt) {
        std::ostringstream s;
        s << "argument 'c01': size " << c->N() << ", expected " << d.m.nt << " (one value per tetrahedron: a P0 function's)";
        fail(fn, s.str());
    }
    const ffc_tets m = hyper_mesh(d);
    ffc_error err;
    if (ffc_hyper_assemble(law, &m, &(*l1)[0], &(*l2)[0], c ? &(*c)[0] : nullptr, &(*u)[0], d.hrp.data(), d.hadj.data(), W,
                           f, tangent ? d.hKv.data() : nullptr, &err))
        hyper_fail(fn, err);
}
} // namespace

basicAC_F0::name_and_type hyper_names[] = {{"c01", &typeid(KN<double> *)}};

double sceneHyperForce(const Named &nm, FFScene *const &C, KN<double> *const &u, KN<double> *const &l1, KN<double> *const &l2,
                       KN<double> *const &f)
{
    const char *fn = "ffcHyperForce";
    SceneData &d = need_scene(fn, C);
    if (!f) fail(fn, "argument 'f': array is not defined");
    std::vector<double> fv(3 * d.nn);
    double W = 0;
    hyper_assemble(fn, nm, d, u, l1, l2, &W, fv.data(), false);
    f->resize(3 * d.nn);
    for (long k = 0; k < 3 * d.nn; k++) (*f)[k] = fv[k];
    return W;
}

long sceneHyperTangent(const Named &nm, FFScene *const &C, KN<double> *const &u, KN<double> *const &l1, KN<double> *const &l2,
                       Matrice_Creuse<double> *const &K)
{
    const char *fn = "ffcHyperTangent";
    SceneData &d = need_scene(fn, C);
    if (!K) fail(fn, "argument 'K': matrix is not defined");
    hyper_assemble(fn, nm, d, u, l1, l2, nullptr, nullptr, true);
    const long nz = (long)d.hKv.size();
    set_matrix(3 * d.nn, nz, d.hKi.data(), d.hKj.data(), d.hKv.data(), false, K);
    return nz;
}

long sceneBulk(const Named &nm, FFScene *const &C, Matrice_Creuse<double> *const &K)
{
    const char *fn = "ffcBulk";
    SceneData &d = need_scene(fn, C);
    std::vector<long> Ti, Tj;
    std::vector<double> Tv;
    const long n = matrix_triplets(fn, "K", K, Ti, Tj, Tv);
    if (n != 3 * d.nn) {
        std::ostringstream s;
        s << "argument 'K': " << n << " x " << n << ", expected " << 3 * d.nn << " x " << 3 * d.nn
          << " (3 dofs per node of the scene's displacement space)";
        fail(fn, s.str());
    }
    const long mmax = nm.integer(0, 4000);
    if (mmax < 0) fail(fn, "argument 'maxContactDofs': " + std::to_string(mmax) + " must be >= 0");
    long bad = -1;
    int st = ffc_scene_set_bulk(d.s, n, (long)Ti.size(), Ti.data(), Tj.data(), Tv.data(), mmax, &bad);
    if (st == FFC_ERR_SINGULAR) {
        std::ostringstream s;
        s << "argument 'K': diagonal entry " << bad << " is not positive (a bulk stiffness is positive definite once its Dirichlet rows are set)";
        fail(fn, s.str());
    }
    if (st == FFC_ERR_INDEX || st == FFC_ERR_NONFINITE) {
        std::ostringstream s;
        s << "argument 'K': entry (" << Ti[bad] << ", " << Tj[bad] << ") = " << num(Tv[bad]) << ": " << ffc_strerror(st);
        fail(fn, s.str());
    }
    if (st) scene_error(fn, st, bad, "the bulk matrix");
    return n;
}

// ffcSolve(C, Kc, b, x): x = (K + Kc)^-1 b with the K of ffcBulk. Returns 0
// solved, 1 not solved (K + Kc singular: a body without support), 2 the
// contact tangent touches more dofs than maxContactDofs (solve otherwise).
long sceneSolve(const Named &, FFScene *const &C, Matrice_Creuse<double> *const &Kc, KN<double> *const &b,
                KN<double> *const &x)
{
    const char *fn = "ffcSolve";
    SceneData &d = need_scene(fn, C);
    const long n = 3 * d.nn;
    std::vector<long> Ti, Tj;
    std::vector<double> Tv;
    const long nk = matrix_triplets(fn, "Kc", Kc, Ti, Tj, Tv);
    if (nk != n) {
        std::ostringstream s;
        s << "argument 'Kc': " << nk << " x " << nk << ", expected " << n << " x " << n;
        fail(fn, s.str());
    }
    if (!b) fail(fn, "argument 'b': array is not defined");
    if (b->N() != n) {
        std::ostringstream s;
        s << "argument 'b': size " << b->N() << ", expected " << n;
        fail(fn, s.str());
    }
    need_finite(fn, "b", b);
    if (!x) fail(fn, "argument 'x': array is not defined");
    std::vector<double> xv(n), bv(n);
    for (long i = 0; i < n; i++) bv[i] = (*b)[i];
    long bad = -1;
    int st = ffc_scene_solve(d.s, (long)Ti.size(), Ti.data(), Tj.data(), Tv.data(), bv.data(), xv.data(), &bad);
    if (st == FFC_ERR_EMPTY) fail(fn, "argument 'C': no bulk matrix yet (ffcBulk(C, K) first)");
    if (st == FFC_ERR_NONFINITE || st == FFC_ERR_INDEX) {
        std::ostringstream s;
        s << "argument 'Kc': entry (" << Ti[bad] << ", " << Tj[bad] << ") = " << num(Tv[bad]) << ": " << ffc_strerror(st);
        fail(fn, s.str());
    }
    if (st == FFC_ERR_SINGULAR) return 1;
    if (st == FFC_ERR_CAPACITY) return 2;
    if (st) bulk_error(fn, d, st, bad, "the linear solve");
    x->resize(n);
    for (long i = 0; i < n; i++) (*x)[i] = xv[i];
    return 0;
}

// ffcNewton(C, r, u, hist, tol = , rtol = 0, maxIter = 25, maxLineSearch = 8,
// lsTol = 0.5, tangent = "consistent", maxDofs = 0, minIter = 0, [v, dt, dvdu]): Newton on the condensed contact
// problem (ffc_scene_newton) from u with its residual r, u updated in
// place (converged when |rho| <= max(tol, rtol x the contact force));
// hist = |rho| at each iteration. tangent: "consistent", "material",
// "ranked" (the material one as low-rank node terms: a dense system of
// one to four unknowns per active slave node; nodal pairs only) or "auto"
// (ranked when every pair is nodal and frictionless, else consistent).
// Returns 0 converged, 1 iteration
// limit, 2 no descent direction, 3 not factorizable (singular), 4 more
// contact dofs than maxDofs (0: the bulk's maxContactDofs); u is kept on 3
// and 4.
basicAC_F0::name_and_type newton_names[] = {{"tol", &typeid(double)},       {"maxIter", &typeid(long)},
                                            {"maxLineSearch", &typeid(long)}, {"lsTol", &typeid(double)},
                                            {"tangent", &typeid(string *)},  {"v", &typeid(KN<double> *)},
                                            {"dt", &typeid(double)},         {"dvdu", &typeid(double)},
                                            {"rtol", &typeid(double)},       {"maxDofs", &typeid(long)},
                                            {"minIter", &typeid(long)}};

long sceneNewton(const Named &nm, FFScene *const &C, KN<double> *const &r, KN<double> *const &u,
                 KN<double> *const &hist)
{
    const char *fn = "ffcNewton";
    SceneData &d = need_scene(fn, C);
    const long n = 3 * d.nn;
    const double *pr = need_scene_u(fn, d, r, "r");
    const double *pu = need_scene_u(fn, d, u);
    if (!hist) fail(fn, "argument 'hist': array is not defined");
    need_not_inverted(fn, d, pu);
    need_penalties(fn, d);
    ffc_newton_opts o = ffc_newton_defaults();
    if (!nm.has(0)) fail(fn, "argument 'tol': missing (the force tolerance of the residual, > 0)");
    o.ftol = nm.real(0, 0);
    if (!(o.ftol > 0) || std::isinf(o.ftol)) fail(fn, "argument 'tol': " + num(o.ftol) + " must be finite and > 0");
    const long mi = nm.integer(1, 25), ml = nm.integer(2, 8);
    if (mi < 1 || mi > 100000) fail(fn, "argument 'maxIter': " + std::to_string(mi) + " must be in 1..100000");
    if (ml < 0 || ml > 1000) fail(fn, "argument 'maxLineSearch': " + std::to_string(ml) + " must be in 0..1000");
    o.max_iter = (int)mi;
    o.max_ls = (int)ml;
    o.ls_tol = nm.real(3, 0.5);
    if (!(o.ls_tol > 0 && o.ls_tol < 1)) fail(fn, "argument 'lsTol': " + num(o.ls_tol) + " must be in (0, 1)");
    o.frel = nm.real(8, 0);
    o.max_dofs = nm.integer(9, 0);
    const long mn = nm.integer(10, 0);
    if (mn < 0 || mn > 1) fail(fn, "argument 'minIter': " + std::to_string(mn) + " must be 0 or 1");
    o.min_iter = (int)mn;
    if (o.max_dofs < 0) fail(fn, "argument 'maxDofs': " + std::to_string(o.max_dofs) + " must be >= 0 (0: the bulk's maxContactDofs)");
    if (!(o.frel >= 0) || std::isinf(o.frel)) fail(fn, "argument 'rtol': " + num(o.frel) + " must be finite and >= 0");
    const std::string t = nm.str(4, "consistent");
    if (t == "consistent") o.tangent = FFC_TANGENT_CONSISTENT;
    else if (t == "material") o.tangent = FFC_TANGENT_MATERIAL;
    else if (t == "ranked") o.tangent = FFC_TANGENT_RANKED;
    else if (t == "auto") { // ranked when every pair is nodal and none has friction, else consistent
        o.tangent = FFC_TANGENT_RANKED;
        for (int k = 0; k < ffc_scene_npairs(d.s); k++) {
            ffc_pair_opts po;
            ffc_scene_pair_opts(d.s, k, &po);
            if (!po.nodal || po.mu > 0) o.tangent = FFC_TANGENT_CONSISTENT;
        }
    } else fail(fn, "argument 'tangent': \"" + t + "\" is not \"consistent\", \"material\", \"ranked\" or \"auto\"");
    for (int k = 0; k < ffc_scene_npairs(d.s); k++) {
        ffc_pair_opts po;
        ffc_scene_pair_opts(d.s, k, &po);
        if (po.method == FFC_METHOD_NTS)
            fail(fn, "argument 'C': pair " + std::to_string(k) + " is node-to-surface; the condensed Newton takes augmented Lagrangian pairs");
        if (o.tangent == FFC_TANGENT_RANKED && !po.nodal)
            fail(fn, "argument 'tangent': \"ranked\" needs nodal multipliers, and pair " + std::to_string(k) + " has them at quadrature points (nodal = 0)");
    }
    scene_motion(fn, nm, d, 5, 6, 7);
    std::vector<double> uv(pu, pu + n);
    long bad = -1;
    int st = ffc_scene_newton(d.s, pr, uv.data(), &o, &d.newton, &bad);
    if (st == FFC_ERR_EMPTY) fail(fn, "argument 'C': no bulk matrix yet (ffcBulk(C, K) first)");
    if (st == FFC_ERR_SINGULAR) return FFC_NEWTON_LINEAR;
    if (st == FFC_ERR_CAPACITY) return FFC_NEWTON_CAPACITY;
    if (st < 0) bulk_error(fn, d, st, bad, "the condensed Newton");
    for (long i = 0; i < n; i++) (*u)[i] = uv[i];
    hist->resize(d.newton.nhist);
    for (int i = 0; i < d.newton.nhist; i++) (*hist)[i] = d.newton.hist[i];
    return st;
}

// ffcSolverStat(C, name): a counter of the bulk solves (see ffc_solve_info).
double sceneSolverStat(const Named &, FFScene *const &C, string *const &name)
{
    const char *fn = "ffcSolverStat";
    SceneData &d = need_scene(fn, C);
    ffc_solve_info in;
    ffc_scene_solve_info(d.s, &in);
    const std::string k = name ? *name : "";
    if (k == "factorizations") return in.factorizations;
    if (k == "columns") return in.columns;
    if (k == "solves") return in.solves;
    if (k == "backsolves") return in.backsolves;
    if (k == "refinements") return in.refinements;
    if (k == "keptLU") return in.kept;
    if (k == "contactDofs") return in.m;
    if (k == "shift") return in.shift;
    if (k == "shiftedDofs") return in.shifted;
    if (k == "rcond") return in.rcond;
    if (k == "residual") return in.residual;
    if (k == "newtonIterations") return d.newton.iters;
    if (k == "evaluations") return d.newton.evals;
    if (k == "evaluationsShared") return d.newton.evals_shared;
    if (k == "evalTime") return d.newton.t_eval;
    if (k == "fallbacks") return d.newton.fallbacks;
    if (k == "condensedDofs") return d.newton.m;
    if (k == "support") return d.newton.support;
    if (k == "ranks") return in.ranks;
    if (k == "factorMB") return in.factor_mb;
    if (k == "factorMBmax") return in.factor_mb_max;
    if (k == "factorTime") return in.t_factor;
    if (k == "columnsTime") return in.t_columns;
    if (k == "backsolveTime") return in.t_backsolves;
    if (k == "reused") return in.reused;
    if (k.compare(0, 4, "full") == 0) {   // ffcFullSolve's
        ffc_solve_info fi = {};
        long an = 0, ch = 0, npd = 0;
        if (d.full) ffc_full_info(d.full, &fi, &an, &ch, &npd);
        if (k == "fullFactorizations") return fi.factorizations;
        if (k == "fullCholesky") return ch;
        if (k == "fullNotPosdef") return npd;
        if (k == "fullAnalyses") return an;
        long ru = 0, kr = 0;
        if (d.full) ffc_full_reuse_info(d.full, &ru, &kr);
        if (k == "fullReused") return ru;
        if (k == "fullKrylov") return kr;
    }
    if (k.compare(0, 9, "iterative") == 0) {   // its iterative path's (solver = "iterative")
        ffc_iterative_info it = {};
        if (d.full) ffc_full_iterative_info(d.full, &it);
        if (k == "iterativeSetups") return it.setups;
        if (k == "iterativeSolves") return it.solves;
        if (k == "iterativeIterations") return it.iterations;
        if (k == "iterativeLast") return it.last_iterations;
        if (k == "iterativeSetupTime") return it.t_setup;
        if (k == "iterativeSolveTime") return it.t_solve;
    }
    fail(fn, "argument 'name': \"" + k + "\" is not one of factorizations, columns, solves, backsolves, refinements, keptLU, contactDofs, shift, shiftedDofs, rcond, residual, newtonIterations, evaluations, evaluationsShared, evalTime, fallbacks, condensedDofs, support, ranks, factorMB, factorMBmax, factorTime, columnsTime, backsolveTime, reused, fullFactorizations, fullCholesky, fullNotPosdef, fullAnalyses, fullReused, fullKrylov, iterativeSetups, iterativeSolves, iterativeIterations, iterativeLast, iterativeSetupTime, iterativeSolveTime");
    return 0;
}

// ffcParallelSolve(A, b, x): A x = b by parallel MUMPS over the ranks of
// FreeFem++-mpi (every rank the same A and b; x on every rank). 0 solved,
// 1 singular (the caller cuts the step, as for a failed UMFPACK solve).
long parallelSolve(Matrice_Creuse<double> *const &A, KN<double> *const &b, KN<double> *const &x)
{
    return parallelSolveOwn(A, b, x, 0);
}
// ffcParallelSolve(A, b, x, own): own = 1, A is this rank's share (the
// matrix solved is the sum of the ranks' A: each assembled its part of the
// mesh); own = 0, every rank holds the same A.
long parallelSolveOwn(Matrice_Creuse<double> *const &A, KN<double> *const &b, KN<double> *const &x, const long &own)
{
    const char *fn = "ffcParallelSolve";
    int ranks, fcomm;
    ffc_mpi_world(nullptr, &ranks, &fcomm);
    if (ranks < 2)
        fail(fn, "needs several ranks (sh scripts/ff -np N, the plugin built with MPI); one process solves with set(A, solver = UMFPACK)");
    std::vector<long> Ti, Tj;
    std::vector<double> Tv;
    const long n = matrix_triplets(fn, "A", A, Ti, Tj, Tv);
    if (!b) fail(fn, "argument 'b': array is not defined");
    if (b->N() != n) fail(fn, "argument 'b': size " + std::to_string(b->N()) + ", expected " + std::to_string(n));
    need_finite(fn, "b", b);
    if (!x) fail(fn, "argument 'x': array is not defined");
    std::vector<double> bv(n), xv(n);
    for (long i = 0; i < n; i++) bv[i] = (*b)[i];
    if (own != 0 && own != 1) fail(fn, "argument 'own': " + std::to_string(own) + " is neither 0 nor 1");
    const ffc_parallel par = {FFC_ENGINE_MUMPS, fcomm, (int)own, 0};
    long bad = -1;
    const int st = ffc_parallel_solve(&par, n, (long)Ti.size(), Ti.data(), Tj.data(), Tv.data(), bv.data(), xv.data(), &bad);
    if (st == FFC_ERR_SINGULAR) return 1;
    if (st == FFC_ERR_NONFINITE || st == FFC_ERR_INDEX) {
        std::ostringstream s;
        s << "argument 'A': entry (" << Ti[bad] << ", " << Tj[bad] << ") = " << num(Tv[bad]) << ": " << ffc_strerror(st);
        fail(fn, s.str());
    }
    if (st) fail(fn, ffc_strerror(st));
    x->resize(n);
    for (long i = 0; i < n; i++) (*x)[i] = xv[i];
    return 0;
}

namespace {

// the full solver's iterative path as the scene's settings say (solver =
// "iterative": PETSc, its preconditioner and tolerances, the rigid-body
// modes of the scene's nodes, the ranks of FreeFem++-mpi), set again
// when they change
void iterative_path(const char *fn, SceneData &d)
{
    const ffc_settings *st = ffc_scene_settings(d.s);
    char solver[32] = "", pc[32] = "";
    double tol = 0, maxit = 0;
    ffc_settings_word(st, "solver", solver, sizeof solver);
    ffc_settings_word(st, "preconditioner", pc, sizeof pc);
    ffc_settings_get(st, "krylovTol", &tol);
    ffc_settings_get(st, "krylovMax", &maxit);
    int rank = 0, ranks = 1, fcomm = 0;
    ffc_mpi_world(&rank, &ranks, &fcomm);
    const bool on = std::string(solver) == "iterative";
    std::ostringstream key;
    key.precision(17);
    key << on << " " << pc << " " << tol << " " << maxit << " " << ranks;
    if (key.str() == d.iterativeKey) return;
    const std::vector<double> &X = d.order == 1 ? d.m.X : d.p2.X2;
    const std::string p(pc);
    const ffc_iterative o = {on, ranks > 1, fcomm, p == "hypre" ? FFC_PC_HYPRE : p == "mumps" ? FFC_PC_MUMPS : FFC_PC_GAMG,
                             tol, (long)maxit, d.nn, X.data()};
    const int r = ffc_full_set_iterative(d.full, &o);
    if (r == FFC_ERR_UNAVAILABLE)
        fail(fn, "solver = \"iterative\" needs PETSc: this plugin was built without it (sh scripts/setup.sh installs "
                 "libpetsc-real-dev; then make)");
    if (r) fail(fn, std::string("solver = \"iterative\": ") + ffc_strerror(r));
    d.iterativeKey = key.str();
}

} // namespace

// ffcFullSolve(C, A, b, x, symmetric = 0, reuse = the scene's reuseKrylov):
// x = A^-1 b for a general sparse A of the scene's size or any other (a
// full Newton system, a saddle matrix, the mass matrix) by UMFPACK in C,
// or, with symmetric = 1 (the caller knows A is symmetric), by CHOLMOD's
// LL^T where A is positive definite; each engine's analysis kept while
// the matrices' entries lie in its pattern, and (reuse > 0) its last
// factor the preconditioner of GMRES (at most reuse iterations) before a
// new factorization; 0 solved, 1 singular (an exactly zero pivot; the
// caller checks the residual, as a tiny pivot gives a huge x), 2 the
// iterative path (solver = "iterative") did not converge in krylovMax;
// block = a real[int] of A's size: its nonzero entries name the dofs that
// path's preconditioner solves exactly after each multigrid cycle (the
// dofs the contact couples); plus = a second matrix of A's size: the
// system is A + plus, summed in C (a Newton system K + Kc without the
// script forming the sum)
basicAC_F0::name_and_type full_names[] = {{"symmetric", &typeid(long)}, {"reuse", &typeid(long)}, {"block", &typeid(KN<double> *)},
                                          {"plus", &typeid(Matrice_Creuse<double> *)}};
long sceneFullSolve(const Named &nm, FFScene *const &C, Matrice_Creuse<double> *const &A, KN<double> *const &b,
                    KN<double> *const &x)
{
    const char *fn = "ffcFullSolve";
    SceneData &d = need_scene(fn, C);
    std::vector<long> Ti, Tj;
    std::vector<double> Tv;
    const long n = matrix_triplets(fn, "A", A, Ti, Tj, Tv);
    if (nm.has(3)) {   // plus: its entries after A's (the full solver sums duplicates)
        std::vector<long> Pi, Pj;
        std::vector<double> Pv;
        const long np = matrix_triplets(fn, "plus", GetAny<Matrice_Creuse<double> *>((*nm.e[3])(nm.s)), Pi, Pj, Pv);
        if (np != n) fail(fn, "argument 'plus': " + std::to_string(np) + " x " + std::to_string(np) + ", A is " + std::to_string(n) + " x " + std::to_string(n));
        Ti.insert(Ti.end(), Pi.begin(), Pi.end());
        Tj.insert(Tj.end(), Pj.begin(), Pj.end());
        Tv.insert(Tv.end(), Pv.begin(), Pv.end());
    }
    if (!b) fail(fn, "argument 'b': array is not defined");
    if (b->N() != n) fail(fn, "argument 'b': size " + std::to_string(b->N()) + ", expected " + std::to_string(n));
    need_finite(fn, "b", b);
    if (!x) fail(fn, "argument 'x': array is not defined");
    const long sym = nm.integer(0, 0);
    if (sym != 0 && sym != 1) fail(fn, "argument 'symmetric': " + std::to_string(sym) + " is not 0 or 1");
    double rdef = 0;
    ffc_settings_get(ffc_scene_settings(d.s), "reuseKrylov", &rdef);
    const long reuse = nm.integer(1, (long)rdef);
    if (reuse < 0 || reuse > 1000) fail(fn, "argument 'reuse': " + std::to_string(reuse) + " is not in [0, 1000]");
    if (!d.full && ffc_full_create(&d.full)) fail(fn, "out of memory for the full solver");
    ffc_full_set_reuse(d.full, reuse);
    iterative_path(fn, d);
    if (nm.has(2)) {   // the iterative path's exact block: the dofs where block != 0
        KN<double> *bk = nm.array(2);
        if (!bk || bk->N() != n)
            fail(fn, "argument 'block': size " + std::to_string(bk ? bk->N() : 0) + ", expected " + std::to_string(n));
        std::vector<long> dofs;
        for (long i = 0; i < n; i++)
            if ((*bk)[i] != 0) dofs.push_back(i);
        const int sb = ffc_full_set_block(d.full, n, (long)dofs.size(), dofs.data());
        if (sb) fail(fn, std::string("argument 'block': ") + ffc_strerror(sb));
    }
    std::vector<double> bv(n), xv(n);
    for (long i = 0; i < n; i++) bv[i] = (*b)[i];
    ffc_error err = {};
    const int st = ffc_full_solve(d.full, n, (long)Ti.size(), Ti.data(), Tj.data(), Tv.data(), (int)sym, bv.data(), xv.data(), &err);
    d.solveMessage = st ? err.msg : "";
    if (st == FFC_ERR_SINGULAR) return 1;
    if (st == FFC_ERR_NOCONV) return 2;
    // (an entry of A the checks refused names the argument; an engine's
    // failure, such as an option PETSc refused, speaks for itself)
    if (st) fail(fn, err.msg[0] && err.where != FFC_AT_TRIPLET ? std::string(err.msg)
                                                             : std::string("argument 'A': ") + (err.msg[0] ? err.msg : ffc_strerror(st)));
    x->resize(n);
    for (long i = 0; i < n; i++) (*x)[i] = xv[i];
    return 0;
}

// ffcSolveMessage(C): why the last ffcFullSolve did not solve, in the
// engine's words ("" after one that did): the Krylov reason and the
// residual reached where it returned 2
string *sceneSolveMessage(const Named &nm, FFScene *const &C)
{
    SceneData &d = need_scene("ffcSolveMessage", C);
    return Add2StackOfPtr2Free(nm.s, new string(d.solveMessage));
}

// Node-to-surface pairs. ffcNTSStep(C): a new load step (per-step flips,
// kept facets and forces cleared). ffcRows(C, u, fixed, B, Bf, Cm, c): the
// constraint rows of every node-to-surface pair at u (see ffc_nts_rows),
// without the columns of dofs with fixed != 0 (moved to c; > 0: held at
// zero, no friction row along it in the contact plane); returns the
// rows. ffcUpdate(C, u, m): after the saddle-point solve, the forces from
// the multipliers m and the transitions; returns the state changes.
long sceneNtsStep(const Named &, FFScene *const &C)
{
    ffc_scene_nts_step(need_scene("ffcNTSStep", C).s);
    return 0;
}

namespace {

void need_nts_scale(const char *fn, SceneData &d, int st, long bad)
{
    if (st == FFC_ERR_VALUE) {
        std::ostringstream s;
        s << "pair " << bad << " (" << d.labels[bad] << "): node-to-surface rows need a scale: give scale = ... in ffcAddPair, or the bulk matrix with ffcBulk(C, K)";
        fail(fn, s.str());
    }
}

// the constraint rows (Bi, Bj, Bv)[nt] of nr rows as FreeFEM matrices: B,
// the force directions Bf (Fv), C (the columns >= n: the multipliers' part
// of sliding rows) and the right-hand side c
void rows_to_matrices(int n, long nt, long nr, const std::vector<long> &Bi, const std::vector<long> &Bj,
                      const std::vector<double> &Bv, const std::vector<double> &Fv, const std::vector<double> &rhs,
                      Matrice_Creuse<double> *B, Matrice_Creuse<double> *Bf, Matrice_Creuse<double> *C,
                      KN<double> *cv)
{
    HashMatrix<int, double> *hb = new HashMatrix<int, double>((int)nr, n, (int)nt, 0);
    HashMatrix<int, double> *hf = new HashMatrix<int, double>((int)nr, n, (int)nt, 0);
    HashMatrix<int, double> *hc = new HashMatrix<int, double>((int)nr, (int)nr, 0, 0);
    for (long t = 0; t < nt; t++) {
        if (Bj[t] >= n) {
            (*hc)((int)Bi[t], (int)(Bj[t] - n)) += Bv[t];
            continue;
        }
        (*hb)((int)Bi[t], (int)Bj[t]) += Bv[t];
        (*hf)((int)Bi[t], (int)Bj[t]) += Fv[t];
    }
    B->A.master(hb);
    B->typemat = 0;
    Bf->A.master(hf);
    Bf->typemat = 0;
    C->A.master(hc);
    C->typemat = 0;
    cv->resize(nr);
    for (long r = 0; r < nr; r++) (*cv)[r] = rhs[r];
}

} // namespace

long sceneRows(const Named &, FFScene *const &C, KN<double> *const &u, KN<double> *const &fixed,
               Matrice_Creuse<double> *const &B, Matrice_Creuse<double> *const &Bf, Matrice_Creuse<double> *const &Cm,
               KN<double> *const &cv)
{
    const char *fn = "ffcRows";
    SceneData &d = need_scene(fn, C);
    const double *pu = need_scene_u(fn, d, u);
    const double *pf = need_scene_u(fn, d, fixed, "fixed");
    if (!B) fail(fn, "argument 'B': matrix is not defined");
    if (!Bf) fail(fn, "argument 'Bf': matrix is not defined");
    if (!Cm) fail(fn, "argument 'Cm': matrix is not defined");
    if (!cv) fail(fn, "argument 'c': array is not defined");
    need_not_inverted(fn, d, pu);
    long nt = 0, nr = 0, bad = -1;
    int st = ffc_scene_nts_rows(d.s, pu, pf, 0, nullptr, nullptr, nullptr, nullptr, 0, nullptr, &nt, &nr, &bad);
    std::vector<long> Bi(nt + 1), Bj(nt + 1);
    std::vector<double> Bv(nt + 1), Fv(nt + 1), rhs(nr + 1);
    if (st == FFC_OK || st == FFC_ERR_CAPACITY)
        st = ffc_scene_nts_rows(d.s, pu, pf, nt, Bi.data(), Bj.data(), Bv.data(), Fv.data(), nr, rhs.data(), &nt, &nr, &bad);
    need_nts_scale(fn, d, st, bad);
    if (st) scene_error(fn, st, bad, "the node-to-surface rows");
    const int n = (int)(3 * d.nn);
    rows_to_matrices(n, nt, nr, Bi, Bj, Bv, Fv, rhs, B, Bf, Cm, cv);
    return nr;
}

// ffcNTSSolve(C, u, fixed, f, x, m): the node-to-surface saddle point of
// the rows at u, [K Bf'; B Cm] [x; m] = [f; c], solved on the factored
// bulk (ffcBulk): x and m (resized to the rows). Returns 0, 1 when the
// system is singular or the solve inaccurate, 2 when the rows touch more
// contact dofs than the bulk takes (the caller's fallback: ffcRows and a
// sparse solve).
long sceneNTSSolve(const Named &, FFScene *const &C, KN<double> *const &u, KN<double> *const &fixed,
                   KN<double> *const &f, KN<double> *const &x, KN<double> *const &m)
{
    const char *fn = "ffcNTSSolve";
    SceneData &d = need_scene(fn, C);
    const double *pu = need_scene_u(fn, d, u);
    const double *pfix = need_scene_u(fn, d, fixed, "fixed");
    const double *pf = need_scene_u(fn, d, f, "f");
    if (!x) fail(fn, "argument 'x': array is not defined");
    if (!m) fail(fn, "argument 'm': array is not defined");
    need_not_inverted(fn, d, pu);
    const long n = 3 * d.nn;
    std::vector<double> xv(n);
    std::vector<double> &mv = d.ntsM;
    if (mv.empty()) mv.resize(64);
    long nr = 0, bad = -1;
    int st = ffc_scene_nts_solve(d.s, pu, pfix, pf, xv.data(), (long)mv.size(), mv.data(), &nr, &bad);
    if (st == FFC_ERR_CAPACITY && nr > (long)mv.size()) {   // (more rows than ever: the rows are made again)
        mv.resize(nr);
        st = ffc_scene_nts_solve(d.s, pu, pfix, pf, xv.data(), nr, mv.data(), &nr, &bad);
    }
    if (st == FFC_ERR_EMPTY) fail(fn, "argument 'C': no bulk matrix yet (ffcBulk(C, K) first)");
    need_nts_scale(fn, d, st, bad);
    if (st == FFC_ERR_SINGULAR) return 1;
    if (st == FFC_ERR_CAPACITY) return 2;
    if (st) bulk_error(fn, d, st, bad, "the node-to-surface solve");
    x->resize(n);
    for (long i = 0; i < n; i++) (*x)[i] = xv[i];
    m->resize(nr);
    for (long r = 0; r < nr; r++) (*m)[r] = mv[r];
    return 0;
}

long sceneUpdate(const Named &, FFScene *const &C, KN<double> *const &u, KN<double> *const &m)
{
    const char *fn = "ffcUpdate";
    SceneData &d = need_scene(fn, C);
    const double *pu = need_scene_u(fn, d, u);
    if (!m) fail(fn, "argument 'm': array is not defined");
    need_finite(fn, "m", m);
    long changes = 0, bad = -1;
    int st = ffc_scene_nts_update(d.s, pu, m->N(), m->N() ? &(*m)[0] : nullptr, &changes, &bad);
    if (st == FFC_ERR_SIZE) {
        std::ostringstream s;
        s << "argument 'm': size " << m->N() << ", expected the " << bad << " multipliers of the rows of the last ffcRows";
        fail(fn, s.str());
    }
    need_nts_scale(fn, d, st, bad);
    if (st) scene_error(fn, st, bad, "the node-to-surface update");
    return changes;
}

// ffcNTSForce(C, R): the contact residual of the node-to-surface pairs
// from their last ffcUpdate (ffcResidual leaves them out), into R (resized
// to the scene's dofs); returns 0.
long sceneNtsForce(const Named &, FFScene *const &C, KN<double> *const &R)
{
    const char *fn = "ffcNTSForce";
    SceneData &d = need_scene(fn, C);
    if (!R) fail(fn, "argument 'R': array is not defined");
    const long n = 3 * d.nn;
    std::vector<double> F(n, 0.0);
    int st = ffc_scene_nts_force(d.s, F.data());
    if (st) scene_error(fn, st, -1, "the node-to-surface forces");
    R->resize(n);
    for (long i = 0; i < n; i++) (*R)[i] = F[i];
    return 0;
}

} // namespace ffc_shim
