// ffcontact.cpp: FreeFEM shim of the ffcontact C kernels: converts meshes and
// arrays to plain C arrays, calls C, turns status codes into ExecError.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <sstream>
#include <string>
#include <vector>

#include "ffc.h"

using namespace Fem2D;

namespace {

// Plain-array view of a tetrahedral mesh and its boundary faces.
struct MeshArrays {
    long nv = 0, nbe = 0;
    std::vector<double> X;     // [nv*3] vertex coordinates
    std::vector<long> be;      // [nbe*3] boundary face vertices
    std::vector<long> belab;   // [nbe] boundary face labels
    std::vector<long> beopp;   // [nbe] vertex of the adjacent tet opposite the face
};

void mesh_arrays(const Mesh3 &Th, MeshArrays &m)
{
    m.nv = Th.nv;
    m.nbe = Th.nbe;
    m.X.resize(3 * m.nv);
    for (long i = 0; i < m.nv; i++) {
        const R3 &P = Th(i);
        m.X[3 * i] = P.x;
        m.X[3 * i + 1] = P.y;
        m.X[3 * i + 2] = P.z;
    }
    m.be.resize(3 * m.nbe);
    m.belab.resize(m.nbe);
    m.beopp.resize(m.nbe);
    for (long k = 0; k < m.nbe; k++) {
        const Mesh3::BorderElement &B = Th.be(k);
        for (int j = 0; j < 3; j++) m.be[3 * k + j] = Th(B[j]);
        m.belab[k] = B.lab;
        int ie = 0;
        int it = Th.BoundaryElement(k, ie);
        m.beopp[k] = Th(Th[it][ie]);
    }
}

[[noreturn]] void fail(const std::string &fn, const std::string &what)
{
    ExecError(fn + ": " + what);
    throw 0; // not reached: ExecError throws
}

std::string labels_present(const MeshArrays &m)
{
    long n = ffc_labels_present(m.nbe, m.belab.data(), 0, nullptr);
    std::vector<long> l(n > 0 ? n : 0);
    if (n > 0) ffc_labels_present(m.nbe, m.belab.data(), n, l.data());
    std::ostringstream s;
    s << "{";
    for (long i = 0; i < n; i++) s << (i ? ", " : "") << l[i];
    s << "}";
    return s.str();
}

// a real as text, NaN and Inf spelled out
std::string num(double v)
{
    if (std::isnan(v)) return "NaN";
    if (std::isinf(v)) return v > 0 ? "+Inf" : "-Inf";
    std::ostringstream s;
    s << v;
    return s.str();
}

const Mesh3 &need_mesh(const char *fn, pmesh3 pTh)
{
    if (!pTh) fail(fn, "argument 'Th': the mesh is not defined");
    return *pTh;
}

// Displacement array u[] of a [P1,P1,P1] function: 3*nv values.
const double *need_disp(const char *fn, KN<double> *u, long nv)
{
    if (!u) fail(fn, "argument 'u': array is not defined");
    if (u->N() != 3 * nv) {
        std::ostringstream s;
        s << "argument 'u': size " << u->N() << ", expected 3*nv = " << 3 * nv
          << " (the coefficients of a [P1,P1,P1] displacement)";
        fail(fn, s.str());
    }
    for (long i = 0; i < u->N(); i++)
        if (!std::isfinite((*u)[i])) {
            std::ostringstream s;
            s << "argument 'u': u[" << i << "] = " << num((*u)[i])
              << " is not finite (vertex " << i / 3 << ", component " << i % 3 << ")";
            fail(fn, s.str());
        }
    return &(*u)[0];
}

// Facet array (argument `arg`): 3 vertex indices per facet.
long need_facets(const char *fn, const char *arg, KN<long> *F, long nv)
{
    const std::string a = std::string("argument '") + arg + "': ";
    if (!F) fail(fn, a + "array is not defined");
    if (F->N() == 0) fail(fn, a + "empty surface (0 facets)");
    if (F->N() % 3) {
        std::ostringstream s;
        s << a << "size " << F->N() << " is not a multiple of 3";
        fail(fn, s.str());
    }
    for (long i = 0; i < F->N(); i++)
        if ((*F)[i] < 0 || (*F)[i] >= nv) {
            std::ostringstream s;
            s << a << arg << "[" << i << "] = " << (*F)[i]
              << " is not a vertex index of the mesh (0.." << nv - 1 << ")";
            fail(fn, s.str());
        }
    return F->N() / 3;
}

void check_surface(const char *fn, const char *arg, long nf, const long *F,
                   const MeshArrays &m, const double *u)
{
    long bad = -1;
    int st = ffc_surface_check(3, nf, F, m.nv, m.X.data(), u, &bad);
    if (st == FFC_OK) return;
    std::ostringstream s;
    s << "argument '" << arg << "': ";
    if (st == FFC_ERR_NONFINITE)
        s << "vertex " << bad << " has a non-finite position";
    else if (st == FFC_ERR_DEGENERATE)
        s << "facet " << bad << " (vertices " << F[3 * bad] << ", " << F[3 * bad + 1]
          << ", " << F[3 * bad + 2] << ") is degenerate: zero area";
    else
        s << "facet " << bad << ": " << ffc_strerror(st);
    fail(fn, s.str());
}

// ffcSurface(Th, labs, F): boundary facets of Th whose label is in labs,
// oriented outward, as 3 global vertex indices each, into F; returns their count.
long ffcSurface(pmesh3 const &pTh, KN<long> *const &labs, KN<long> *const &F)
{
    const char *fn = "ffcSurface";
    const Mesh3 &Th = need_mesh(fn, pTh);
    if (!labs) fail(fn, "argument 'labs': array is not defined");
    if (!F) fail(fn, "argument 'F': array is not defined");
    if (labs->N() == 0) fail(fn, "argument 'labs': empty list of labels");
    MeshArrays m;
    mesh_arrays(Th, m);
    if (m.nbe == 0) fail(fn, "argument 'Th': the mesh has no boundary faces");
    std::vector<long> L(labs->N());
    for (long i = 0; i < labs->N(); i++) L[i] = (*labs)[i];
    std::vector<long> out(3 * m.nbe);
    long bad = -1;
    int st = ffc_surface_select(3, m.nbe, m.be.data(), m.belab.data(), m.beopp.data(), m.nv,
                                m.X.data(), (int)L.size(), L.data(), m.nbe, out.data(), &bad);
    if (st < 0) {
        std::ostringstream s;
        if (st == FFC_ERR_LABEL)
            s << "argument 'labs': no boundary face carries label " << bad
              << "; labels present: " << labels_present(m);
        else if (st == FFC_ERR_DEGENERATE)
            s << "boundary face " << bad << " is degenerate: zero area";
        else
            s << ffc_strerror(st) << " (face " << bad << ")";
        fail(fn, s.str());
    }
    F->resize(3 * (long)st);
    for (long i = 0; i < 3 * (long)st; i++) (*F)[i] = out[i];
    return st;
}

// ffcArea(Th, F, u): area of the surface F in the configuration X + u.
double ffcArea(pmesh3 const &pTh, KN<long> *const &F, KN<double> *const &u)
{
    const char *fn = "ffcArea";
    const Mesh3 &Th = need_mesh(fn, pTh);
    MeshArrays m;
    mesh_arrays(Th, m);
    long nf = need_facets(fn, "F", F, m.nv);
    const double *pu = need_disp(fn, u, m.nv);
    const long *pF = &(*F)[0];
    check_surface(fn, "F", nf, pF, m, pu);
    double A = 0.0;
    int st = ffc_surface_area(3, nf, pF, m.nv, m.X.data(), pu, 2, &A);
    if (st) fail(fn, ffc_strerror(st));
    return A;
}

// ffcNormals(Th, F, u, N): unit outward normal at the centroid of each
// facet of F in the configuration X + u, into N (3 per facet); returns nf.
long ffcNormals(pmesh3 const &pTh, KN<long> *const &F, KN<double> *const &u,
                KN<double> *const &N)
{
    const char *fn = "ffcNormals";
    const Mesh3 &Th = need_mesh(fn, pTh);
    if (!N) fail(fn, "argument 'N': array is not defined");
    MeshArrays m;
    mesh_arrays(Th, m);
    long nf = need_facets(fn, "F", F, m.nv);
    const double *pu = need_disp(fn, u, m.nv);
    const long *pF = &(*F)[0];
    check_surface(fn, "F", nf, pF, m, pu);
    std::vector<double> out(3 * nf);
    long bad = -1;
    int st = ffc_surface_normals(3, nf, pF, m.nv, m.X.data(), pu, out.data(), &bad);
    if (st) fail(fn, ffc_strerror(st));
    N->resize(3 * nf);
    for (long i = 0; i < 3 * nf; i++) (*N)[i] = out[i];
    return nf;
}

// current positions x = X + u of all vertices
std::vector<double> current_positions(const MeshArrays &m, const double *u)
{
    std::vector<double> x(m.X);
    for (size_t i = 0; i < x.size(); i++) x[i] += u[i];
    return x;
}

// Columns of a link row (real[int,int] L(nlinks, FFC_LINK_COLS)).
const long L_SF = 0, L_Q = 1, L_XS1 = 2, L_XS2 = 3, L_MF = 4, L_XM1 = 5, L_XM2 = 6, L_GAP = 7,
           L_NX = 8, L_NY = 9, L_NZ = 10, L_WHERE = 11, L_COLS = 12;

// ffcSearch(Th, u, Fs, Fm, qdeg, crel, cabs, L): links of every quadrature
// point of the slave facets Fs to the master facets Fm in the configuration
// X + u; one row of L per slave point (facet-major); returns the number of
// points with a partner.
long ffcSearch(pmesh3 const &pTh, KN<double> *const &u, KN<long> *const &Fs,
               KN<long> *const &Fm, long const &qdeg, double const &crel,
               double const &cabs, KNM<double> *const &L)
{
    const char *fn = "ffcSearch";
    const Mesh3 &Th = need_mesh(fn, pTh);
    if (!L) fail(fn, "argument 'L': array is not defined");
    if (qdeg < 1 || qdeg > 6) {
        std::ostringstream s;
        s << "argument 'qdeg': " << qdeg << " is not a quadrature degree (1..6)";
        fail(fn, s.str());
    }
    if (!(crel >= 0) || std::isinf(crel)) fail(fn, "argument 'crel': capture distance factor " + num(crel) + " must be finite and >= 0");
    if (!(cabs >= 0) || std::isinf(cabs)) fail(fn, "argument 'cabs': capture distance " + num(cabs) + " must be finite and >= 0");
    MeshArrays m;
    mesh_arrays(Th, m);
    const double *pu = need_disp(fn, u, m.nv);
    long nfs = need_facets(fn, "Fs", Fs, m.nv);
    long nfm = need_facets(fn, "Fm", Fm, m.nv);
    check_surface(fn, "Fs", nfs, &(*Fs)[0], m, pu);
    check_surface(fn, "Fm", nfm, &(*Fm)[0], m, pu);
    std::vector<double> x = current_positions(m, pu);
    ffc_tree *t = nullptr;
    int st = ffc_tree_build(3, nfm, &(*Fm)[0], m.nv, x.data(), &t);
    if (st) fail(fn, std::string("master surface: ") + ffc_strerror(st));
    const long nq = ffc_quad_size((int)qdeg), nl = nfs * nq;
    std::vector<ffc_link> links(nl);
    ffc_search_opts o = ffc_search_defaults();
    o.capture_rel = crel;
    o.capture_abs = cabs;
    st = ffc_search(t, 3, nfs, &(*Fs)[0], m.nv, x.data(), (int)qdeg, &o, nl, links.data());
    ffc_tree_free(t);
    if (st < 0) fail(fn, ffc_strerror(st));
    L->resize(nl, L_COLS);
    KNM<double> &A = *L;
    for (long k = 0; k < nl; k++) {
        const ffc_link &l = links[k];
        A(k, L_SF) = l.sf; A(k, L_Q) = l.q; A(k, L_XS1) = l.xs[0]; A(k, L_XS2) = l.xs[1];
        A(k, L_MF) = l.mf; A(k, L_XM1) = l.xm[0]; A(k, L_XM2) = l.xm[1]; A(k, L_GAP) = l.gap;
        A(k, L_NX) = l.n[0]; A(k, L_NY) = l.n[1]; A(k, L_NZ) = l.n[2]; A(k, L_WHERE) = l.where;
    }
    return st;
}

} // namespace

static void init()
{
    Global.Add("ffcSurface", "(",
               new OneOperator3_<long, pmesh3, KN<long> *, KN<long> *>(ffcSurface));
    Global.Add("ffcArea", "(",
               new OneOperator3_<double, pmesh3, KN<long> *, KN<double> *>(ffcArea));
    Global.Add("ffcSearch", "(",
               new OneOperator8_<long, pmesh3, KN<double> *, KN<long> *, KN<long> *, long, double,
                                 double, KNM<double> *>(ffcSearch));
    Global.Add("ffcNormals", "(",
               new OneOperator4_<long, pmesh3, KN<long> *, KN<double> *, KN<double> *>(ffcNormals));
}

LOADFUNC(init)
