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

// Facet array F: 3 vertex indices per facet.
long need_facets(const char *fn, KN<long> *F, long nv)
{
    if (!F) fail(fn, "argument 'F': array is not defined");
    if (F->N() == 0) fail(fn, "argument 'F': empty surface (0 facets)");
    if (F->N() % 3) {
        std::ostringstream s;
        s << "argument 'F': size " << F->N() << " is not a multiple of 3";
        fail(fn, s.str());
    }
    for (long i = 0; i < F->N(); i++)
        if ((*F)[i] < 0 || (*F)[i] >= nv) {
            std::ostringstream s;
            s << "argument 'F': F[" << i << "] = " << (*F)[i]
              << " is not a vertex index of the mesh (0.." << nv - 1 << ")";
            fail(fn, s.str());
        }
    return F->N() / 3;
}

void check_surface(const char *fn, long nf, const long *F, const MeshArrays &m,
                   const double *u)
{
    long bad = -1;
    int st = ffc_surface_check(3, nf, F, m.nv, m.X.data(), u, &bad);
    if (st == FFC_OK) return;
    std::ostringstream s;
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
    long nf = need_facets(fn, F, m.nv);
    const double *pu = need_disp(fn, u, m.nv);
    const long *pF = &(*F)[0];
    check_surface(fn, nf, pF, m, pu);
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
    long nf = need_facets(fn, F, m.nv);
    const double *pu = need_disp(fn, u, m.nv);
    const long *pF = &(*F)[0];
    check_surface(fn, nf, pF, m, pu);
    std::vector<double> out(3 * nf);
    long bad = -1;
    int st = ffc_surface_normals(3, nf, pF, m.nv, m.X.data(), pu, out.data(), &bad);
    if (st) fail(fn, ffc_strerror(st));
    N->resize(3 * nf);
    for (long i = 0; i < 3 * nf; i++) (*N)[i] = out[i];
    return nf;
}

} // namespace

static void init()
{
    Global.Add("ffcSurface", "(",
               new OneOperator3_<long, pmesh3, KN<long> *, KN<long> *>(ffcSurface));
    Global.Add("ffcArea", "(",
               new OneOperator3_<double, pmesh3, KN<long> *, KN<double> *>(ffcArea));
    Global.Add("ffcNormals", "(",
               new OneOperator4_<long, pmesh3, KN<long> *, KN<double> *, KN<double> *>(ffcNormals));
}

LOADFUNC(init)
