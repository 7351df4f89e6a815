// ffcontact.cpp: FreeFEM shim of the ffcontact C kernels: converts meshes and
// arrays to plain C arrays, calls C, turns status codes into ExecError.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <algorithm>
#include <cstring>
#include <array>
#include <chrono>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "ffc.h"
#include <memory>

using namespace Fem2D;

namespace {

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
    m.nt = Th.nt;
    m.T.resize(4 * m.nt);
    for (long k = 0; k < m.nt; k++)
        for (int j = 0; j < 4; j++) m.T[4 * k + j] = Th(k, j);
    m.be.resize(3 * m.nbe);
    m.belab.resize(m.nbe);
    m.beopp.resize(m.nbe);
    m.betet.resize(m.nbe);
    for (long k = 0; k < m.nbe; k++) {
        const Mesh3::BorderElement &B = Th.be(k);
        for (int j = 0; j < 3; j++) m.be[3 * k + j] = Th(B[j]);
        m.belab[k] = B.lab;
        int ie = 0;
        int it = Th.BoundaryElement(k, ie);
        m.beopp[k] = Th(Th[it][ie]);
        m.betet[k] = it;
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

void p2_arrays(const char *fn, const MeshArrays &m, P2Arrays &p)
{
    p.node.resize(10 * m.nt);
    int st = ffc_p2_number(m.nt, m.T.data(), m.nv, p.node.data(), &p.nn);
    if (st) fail(fn, std::string("P2 numbering: ") + ffc_strerror(st));
    p.X2.resize(3 * p.nn);
    st = ffc_p2_positions(m.nt, m.T.data(), p.node.data(), m.X.data(), p.nn, p.X2.data());
    if (st) fail(fn, std::string("P2 positions: ") + ffc_strerror(st));
    p.vnode.assign(m.nv, -1);
    for (long k = 0; k < m.nt; k++)
        for (int a = 0; a < 4; a++) p.vnode[m.T[4 * k + a]] = p.node[10 * k + a];
}

// The boundary face of each (sorted) vertex triple.
typedef std::map<std::array<long, 3>, long> FaceMap;
FaceMap face_map(const MeshArrays &m)
{
    FaceMap face;
    for (long k = 0; k < m.nbe; k++) {
        std::array<long, 3> key = {m.be[3 * k], m.be[3 * k + 1], m.be[3 * k + 2]};
        std::sort(key.begin(), key.end());
        face[key] = k;
    }
    return face;
}
long face_of(const FaceMap &face, const long v[3])
{
    std::array<long, 3> key = {v[0], v[1], v[2]};
    std::sort(key.begin(), key.end());
    return face.at(key);
}

// The 6 P2 nodes of each of the nf boundary facets F3[nf*3] (vertex
// triples) into out6[nf*6].
void p2_facets(const char *fn, const MeshArrays &m, const P2Arrays &p2, const FaceMap &face, long nf, const long *F3,
               long *out6)
{
    for (long f = 0; f < nf; f++) {
        const long *v = F3 + 3 * f, t = m.betet[face_of(face, v)];
        int st = ffc_p2_face(&m.T[4 * t], &p2.node[10 * t], v, out6 + 6 * f);
        if (st) fail(fn, std::string("P2 face: ") + ffc_strerror(st));
    }
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

// Displacement array u[] of a [P1,P1,P1] (or, with p2 set, [P2,P2,P2])
// function: 3 values per node.
const double *need_disp(const char *fn, KN<double> *u, long nv, bool p2 = false)
{
    if (!u) fail(fn, "argument 'u': array is not defined");
    if (u->N() != 3 * nv) {
        std::ostringstream s;
        s << "argument 'u': size " << u->N() << ", expected " << 3 * nv
          << (p2 ? " (the coefficients of a [P2,P2,P2] displacement: 3 per P2 node)"
                 : " = 3*nv (the coefficients of a [P1,P1,P1] displacement)");
        fail(fn, s.str());
    }
    for (long i = 0; i < u->N(); i++)
        if (!std::isfinite((*u)[i])) {
            std::ostringstream s;
            s << "argument 'u': u[" << i << "] = " << num((*u)[i])
              << " is not finite (" << (p2 ? "node " : "vertex ") << i / 3 << ", component " << i % 3 << ")";
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

// Facets F[nf*nper] against nodes at X + u (u may be NULL): indices,
// finite positions, non-degenerate facets; nper = 3: mesh vertices, 6: P2 nodes.
void check_facets(const char *fn, const char *arg, int nper, long nf, const long *F, long nnodes,
                  const double *X, const double *u)
{
    long bad = -1;
    int st = ffc_surface_check(nper, nf, F, nnodes, X, u, &bad);
    if (st == FFC_OK) return;
    const char *node = nper == 3 ? "vertex" : "node";
    std::ostringstream s;
    s << "argument '" << arg << "': ";
    if (st == FFC_ERR_NONFINITE)
        s << node << " " << bad << " has a non-finite position";
    else if (st == FFC_ERR_DEGENERATE) {
        s << "facet " << bad << " (" << (nper == 3 ? "vertices" : "nodes");
        for (int a = 0; a < nper; a++) s << (a ? ", " : " ") << F[nper * bad + a];
        s << ") is degenerate: zero area";
    } else
        s << "facet " << bad << ": " << ffc_strerror(st);
    fail(fn, s.str());
}

// The boundary facets of Th whose label is in labs (argument `arg`),
// oriented outward, into F; returns their count.
long select_surface(const char *fn, const char *arg, const Mesh3 &Th, KN<long> *labs, KN<long> *F)
{
    const std::string a = std::string("argument '") + arg + "': ";
    if (!labs) fail(fn, a + "array is not defined");
    if (labs->N() == 0) fail(fn, a + "empty list of labels");
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
            s << a << "no boundary face carries label " << bad << "; labels present: " << labels_present(m);
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

// ffcSurface(Th, labs, F): boundary facets of Th whose label is in labs,
// oriented outward, as 3 global vertex indices each, into F; returns their count.
long ffcSurface(pmesh3 const &pTh, KN<long> *const &labs, KN<long> *const &F)
{
    const char *fn = "ffcSurface";
    const Mesh3 &Th = need_mesh(fn, pTh);
    if (!F) fail(fn, "argument 'F': array is not defined");
    return select_surface(fn, "labs", Th, labs, F);
}

// Slave and master label lists: non-empty, disjoint.
long ffcP2Nodes(pmesh3 const &pTh, KN<double> *const &X2)
{
    const char *fn = "ffcP2Nodes";
    const Mesh3 &Th = need_mesh(fn, pTh);
    if (!X2) fail(fn, "argument 'X2': array is not defined");
    MeshArrays m;
    mesh_arrays(Th, m);
    P2Arrays p2;
    p2_arrays(fn, m, p2);
    X2->resize(3 * p2.nn);
    for (long i = 0; i < 3 * p2.nn; i++) (*X2)[i] = p2.X2[i];
    return p2.nn;
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
    check_facets(fn, "F", 3, nf, pF, m.nv, m.X.data(), pu);
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
    check_facets(fn, "F", 3, nf, pF, m.nv, m.X.data(), pu);
    std::vector<double> out(3 * nf);
    long bad = -1;
    int st = ffc_surface_normals(3, nf, pF, m.nv, m.X.data(), pu, out.data(), &bad);
    if (st) fail(fn, ffc_strerror(st));
    N->resize(3 * nf);
    for (long i = 0; i < 3 * nf; i++) (*N)[i] = out[i];
    return nf;
}

long ffcSaveVTK(string *const &file, KNM<double> *const &P)
{
    const char *fn = "ffcSaveVTK";
    if (!file) fail(fn, "argument 'file': no file name");
    if (!P || P->M() != FFC_POINT_COLS) fail(fn, "argument 'P': expected the point array of ffcPoints");
    const long n = P->N();
    std::vector<double> rows(n * FFC_POINT_COLS);
    for (long k = 0; k < n; k++)
        for (long j = 0; j < FFC_POINT_COLS; j++) rows[k * FFC_POINT_COLS + j] = (*P)(k, j);
    int rc = ffc_points_vtk(file->c_str(), n, rows.data());
    if (rc) fail(fn, "argument 'file': cannot write '" + *file + "': " + ffc_strerror(rc));
    return n;
}

// ffcWriteColumns(file, header, A, mask): the rows of the table A
// (real[int,int], one column per quantity) whose mask is non-zero, as text
// under "# header"; returns the number of rows written.
long ffcWriteColumns(string *const &file, string *const &header, KNM<double> *const &A,
                     KN<double> *const &mask)
{
    const char *fn = "ffcWriteColumns";
    if (!file) fail(fn, "argument 'file': no file name");
    if (!A || A->N() == 0) fail(fn, "argument 'A': empty table");
    if (!mask || mask->N() != A->N()) fail(fn, "argument 'mask': one value per row of 'A' expected");
    const long n = A->N();
    const int m = (int)A->M();
    std::vector<double> cols((size_t)n * m), msk(n);
    long rows = 0;
    for (long k = 0; k < n; k++) {
        msk[k] = (*mask)[k];
        rows += msk[k] != 0.0;
        for (long j = 0; j < m; j++) cols[j * n + k] = (*A)(k, j);
    }
    int rc = ffc_write_columns(file->c_str(), header ? header->c_str() : nullptr, n, m, cols.data(), msk.data());
    if (rc) fail(fn, "argument 'file': cannot write '" + *file + "': " + ffc_strerror(rc));
    return rows;
}

// ffcInverted(Th, u): the first tetrahedron that X + u turns inside out or
// collapses, or -1 (a query for line searches: no error).
long ffcInverted(pmesh3 const &pTh, KN<double> *const &u)
{
    const char *fn = "ffcInverted";
    const Mesh3 &Th = need_mesh(fn, pTh);
    MeshArrays m;
    mesh_arrays(Th, m);
    if (!u) fail(fn, "argument 'u': array is not defined");
    std::vector<double> uv(&(*u)[0], &(*u)[0] + u->N());
    if (u->N() != 3 * m.nv) {   // a [P2,P2,P2] displacement: its vertex values
        P2Arrays p2;
        p2_arrays(fn, m, p2);
        if (u->N() != 3 * p2.nn)
            fail(fn, "argument 'u': expected the coefficients of a [P1,P1,P1] or [P2,P2,P2] displacement");
        uv.assign(3 * m.nv, 0.0);
        for (long v = 0; v < m.nv; v++)
            for (int i = 0; i < 3; i++) uv[3 * v + i] = (*u)[3 * p2.vnode[v] + i];
    }
    long bad = -1;
    int st = ffc_volume_check(m.nt, m.T.data(), m.nv, m.X.data(), uv.data(), &bad);
    return st == FFC_OK ? -1 : bad;
}

// ffcTime(): monotonic wall-clock time in seconds (for timings; FreeFEM's
// clock() is processor time, summed over threads).
double ffcTime()
{
    using namespace std::chrono;
    return duration<double>(steady_clock::now().time_since_epoch()).count();
}

// ffcRank(), ffcRanks(): this process's rank and the ranks (0 and 1 in the
// plugin without MPI); ffcRankSum(x), ffcRankMax(x): x summed / largest over
// the ranks (a collective call); ffcBarrier(); ffcPeakMB(): this process's
// peak resident memory (MB).
long ffcRank() { int r; ffc_mpi_world(&r, nullptr, nullptr); return r; }
long ffcRanks() { int n; ffc_mpi_world(nullptr, &n, nullptr); return n; }
double rankReduce(const char *fn, double x, int op)
{
    double v = x;
    const int st = ffc_mpi_allreduce(&v, 1, op);
    if (st) fail(fn, ffc_strerror(st));
    return v;
}
double ffcRankSum(double x) { return rankReduce("ffcRankSum", x, 0); }
// ffcRankSum(v): the array v summed over the ranks, in place (every rank
// passes an array of the same size)
long ffcRankSumArray(KN<double> *const &v)
{
    if (!v) fail("ffcRankSum", "argument 'v': array is not defined");
    const long n = v->N();
    std::vector<double> w(n);
    for (long i = 0; i < n; i++) w[i] = (*v)[i];
    const int st = ffc_mpi_allreduce(w.data(), n, 0);
    if (st) fail("ffcRankSum", ffc_strerror(st));
    for (long i = 0; i < n; i++) (*v)[i] = w[i];
    return n;
}
long ffcRankSumMatrix(Matrice_Creuse<double> *const &A);
double ffcRankMax(double x) { return rankReduce("ffcRankMax", x, 1); }
long ffcBarrier() { return ffc_mpi_barrier(); }
double ffcPeakMB() { return ffc_peak_mb(); }

} // namespace

// ---------------------------------------------------------------------------
// Contact-reduced linear solve (ffc_reduced_*): the compliance G of the
// contact dofs rdof (real[int] of ld x ld, column-major, ld = sqrt(G.n)),
// grown column by column, and the dense system that replaces a
// factorization of K + Kc in a small-strain scene.

// The triplets of a square FreeFEM matrix (a half-stored one expanded).
long matrix_triplets(const char *fn, const char *arg, Matrice_Creuse<double> *K, std::vector<long> &Ti,
                     std::vector<long> &Tj, std::vector<double> &Tv)
{
    if (!K || !K->A) fail(fn, std::string("argument '") + arg + "': matrix is not defined");
    HashMatrix<int, double> *h = dynamic_cast<HashMatrix<int, double> *>((MatriceCreuse<double> *)K->A);
    if (!h) fail(fn, std::string("argument '") + arg + "': not a sparse matrix");
    if (h->n != h->m) {
        std::ostringstream s;
        s << "argument '" << arg << "': " << h->n << " x " << h->m << " matrix, expected a square one";
        fail(fn, s.str());
    }
    const size_t nz = h->nnz;
    Ti.clear(); Tj.clear(); Tv.clear();
    for (size_t k = 0; k < nz; k++) {
        Ti.push_back(h->i[k]); Tj.push_back(h->j[k]); Tv.push_back(h->aij[k]);
        if (h->half && h->i[k] != h->j[k]) { Ti.push_back(h->j[k]); Tj.push_back(h->i[k]); Tv.push_back(h->aij[k]); }
    }
    return h->n;
}

// K = the n x n matrix of the distinct entries (Ci, Cj, Cv)[nk] (half
// stored, the lower triangle's, with lower = true)
void set_matrix(long n, long nk, long *Ci, long *Cj, double *Cv, bool lower, Matrice_Creuse<double> *K)
{
    HashMatrix<int, double> *h = new HashMatrix<int, double>((int)n, (int)n, 0, lower ? 1 : 0);
    h->set(n, n, lower ? 1 : 0, (size_t)nk, Ci, Cj, Cv, 0);   // (distinct entries: no lookups)
    K->A.master(h);
    K->typemat = 0;
}

// The contact tangent's triplets (Ti, Tj, Tv)[nt] of an n x n matrix handed
// to K: duplicates summed in C (the nodal law repeats entries many times);
// lower = 1 keeps the lower triangle, as FreeFEM's half matrices do.
void triplets_to_matrix(const char *fn, long n, long nt, const long *Ti, const long *Tj, const double *Tv, bool lower,
                        Matrice_Creuse<double> *K, const char *what = "the contact tangent")
{
    std::vector<long> Ci(nt > 0 ? nt : 1), Cj(nt > 0 ? nt : 1), rp(n + 1), wk(n);
    std::vector<double> Cv(nt > 0 ? nt : 1);
    const long nz = ffc_triplets_sum(n, nt, Ti, Tj, Tv, Ci.data(), Cj.data(), Cv.data(), rp.data(), wk.data());
    if (nz < 0) fail(fn, std::string(what) + ": " + ffc_strerror((int)nz));
    long nk = 0;   // (the entries kept: all, or the lower triangle's)
    for (long t = 0; t < nz; t++)
        if (!lower || Ci[t] >= Cj[t]) { Ci[nk] = Ci[t]; Cj[nk] = Cj[t]; Cv[nk] = Cv[t]; nk++; }
    set_matrix(n, nk, Ci.data(), Cj.data(), Cv.data(), lower, K);
}

namespace {
// ffcRankSum(A): the matrix A replaced on every rank by the sum of every
// rank's A (pieces of one matrix assembled on parts of the mesh; every
// rank calls it with an n x n matrix of the same n; a half-stored A comes
// back stored whole). Returns the sum's entries.
long ffcRankSumMatrix(Matrice_Creuse<double> *const &A)
{
    const char *fn = "ffcRankSum";
    std::vector<long> Ti, Tj;
    std::vector<double> Tv;
    const long n = matrix_triplets(fn, "A", A, Ti, Tj, Tv);
    double lo = (double)n, hi = (double)n;
    int st = ffc_mpi_allreduce(&lo, 1, 2);
    if (!st) st = ffc_mpi_allreduce(&hi, 1, 1);
    if (st) fail(fn, ffc_strerror(st));
    if (lo != hi) {
        std::ostringstream m;
        m << "argument 'A': " << n << " x " << n << " here, but the ranks' matrices range from " << (long)lo
          << " to " << (long)hi << " rows (every rank passes its piece of one matrix)";
        fail(fn, m.str());
    }
    long total = 0;
    st = ffc_mpi_gather_triplets((long)Tv.size(), Ti.data(), Tj.data(), Tv.data(), 0, nullptr, nullptr, nullptr, &total);
    if (st && st != FFC_ERR_CAPACITY) fail(fn, ffc_strerror(st));
    std::vector<long> Oi(total > 0 ? total : 1), Oj(total > 0 ? total : 1);
    std::vector<double> Ov(total > 0 ? total : 1);
    st = ffc_mpi_gather_triplets((long)Tv.size(), Ti.data(), Tj.data(), Tv.data(), total, Oi.data(), Oj.data(),
                                 Ov.data(), &total);
    if (st) fail(fn, ffc_strerror(st));
    triplets_to_matrix(fn, n, total, Oi.data(), Oj.data(), Ov.data(), false, A, "the ranks' sum");
    HashMatrix<int, double> *h = dynamic_cast<HashMatrix<int, double> *>((MatriceCreuse<double> *)A->A);
    return h ? (long)h->nnz : 0;
}
} // namespace


// The helpers of the scene calls: labels, effects bits, finite arrays, the
// constraint rows of node-to-surface pairs as FreeFEM matrices.
void need_pair_labels(const char *fn, KN<long> *sl, KN<long> *ml)
{
    if (!sl || sl->N() == 0) fail(fn, "argument 'slaveLabs': empty list of labels");
    if (!ml || ml->N() == 0) fail(fn, "argument 'masterLabs': empty list of labels");
    for (long i = 0; i < sl->N(); i++)
        for (long j = 0; j < ml->N(); j++)
            if ((*sl)[i] == (*ml)[j]) {
                std::ostringstream s;
                s << "label " << (*sl)[i] << " is in both 'slaveLabs' and 'masterLabs'";
                fail(fn, s.str());
            }
}

ffc_effects need_effects(const char *fn, long bits, const char *arg = "argument 'opt': effects = opt[1]")
{
    if (bits < 0 || bits > 7) {
        std::ostringstream s;
        s << arg << " = " << bits << " is not a set of effects (bits: 1 friction, 2 dynamic, 4 finite deformation)";
        fail(fn, s.str());
    }
    ffc_effects e = {(bits & 1) ? 1 : 0, (bits & 2) ? 1 : 0, (bits & 4) ? 1 : 0};
    return e;
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

// ---------------------------------------------------------------------------
// Contact scenes (script type ffcScene): a mesh's nodes and any number of
// contact pairs with their own options, links, multipliers and history,
// kept between calls (ffc_scene_*); options by name, statistics by name.

namespace {

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
    const char *name(int i) const { return names[i].name; }
};

const int MAXNAMED = 16;

// A script type's name in words (for messages).
std::string type_word(aType t)
{
    if (t == atype<double>()) return "real";
    if (t == atype<long>()) return "int";
    if (t == atype<bool>()) return "bool";
    if (t == atype<string *>()) return "string";
    if (t == atype<KN<double> *>()) return "real[int]";
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
        Code(func ff, const char *fname, basicAC_F0::name_and_type *nm, int n, const basicAC_F0 &args,
             const Expression *e)
            : f(ff), fn(fname), names(nm)
        {
            for (size_t i = 0; i < sizeof...(A); i++) a[i] = e[i];
            for (int i = 0; i < MAXNAMED; i++) nargs[i] = nullptr;
            args.SetNameParam(n, names, nargs);
        }
        template <size_t... I>
        AnyType call(Stack s, std::index_sequence<I...>) const
        {
            Named nm{names, nargs, s, fn};
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
                    CompileError(s.str());
                }
            }
        Expression e[sizeof...(A)];
        for (size_t i = 0; i < sizeof...(A); i++) e[i] = t[i]->CastTo(args[i]);
        return new Code(f, fn, names, nn, args, e);
    }
};

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
    ~SceneData() { ffc_scene_free(s); }
};

} // namespace

// The script type: a pointer to SceneData, set by ffcScene C(Th, ...).
struct FFScene {
    SceneData *d;
    void init() { d = nullptr; }
    void destroy()
    {
        delete d;
        d = nullptr;
    }
};

namespace {

std::string labels_text(const KN<long> &l)
{
    std::ostringstream s;
    s << "{";
    for (long i = 0; i < l.N(); i++) s << (i ? ", " : "") << l[i];
    s << "}";
    return s.str();
}

SceneData &need_scene(const char *fn, FFScene *C)
{
    if (!C || !C->d || !C->d->s)
        fail(fn, "argument 'C': the scene is not made: declare it with ffcScene C(Th) (or ffcScene C(Th, effects = ..., order = 2))");
    return *C->d;
}

// u (argument 'u') of the scene's mesh: 3 values per node, finite, no
// tetrahedron inverted.
const double *need_scene_u(const char *fn, SceneData &d, KN<double> *u, const char *arg = "u")
{
    const std::string a = std::string("argument '") + arg + "': ";
    if (!u) fail(fn, a + "array is not defined");
    if (u->N() != 3 * d.nn) {
        std::ostringstream s;
        s << a << "size " << u->N() << ", expected " << 3 * d.nn << " = 3 x " << d.nn
          << (d.order == 2 ? " P2 nodes" : " vertices") << " of the scene's mesh (is it the mesh the scene was made with?)";
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

void scene_error(const char *fn, int st, long bad, const char *what)
{
    std::ostringstream s;
    s << what << ": " << ffc_strerror(st);
    if (bad >= 0) s << " (at " << bad << ")";
    if (st == FFC_ERR_DEGENERATE) s << ": an inverted or collapsed facet; did Newton diverge?";
    fail(fn, s.str());
}

// ffcScene C(Th, effects = 0, order = 1, engine = "auto", shareLinks = 1)
basicAC_F0::name_and_type scene_names[] = {
    {"effects", &typeid(long)}, {"order", &typeid(long)}, {"engine", &typeid(string *)}, {"shareLinks", &typeid(long)}};

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
    int st = ffc_scene_create(order == 2 ? 6 : 3, d->nn, X, d->m.nt, T.data(), &fx, &d->s);
    if (st) scene_error(fn, st, -1, "the scene");
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
enum { PO_METHOD, PO_MU, PO_EPSN, PO_EPST, PO_QDEG, PO_NODAL, PO_CREL, PO_CABS, PO_MUD, PO_GTOL, PO_FTOL, PO_FLIPS,
       PO_SCALE, PO_DUAL, PO_DUALT, PO_N };
basicAC_F0::name_and_type pair_names[] = {
    {"method", &typeid(string *)}, {"mu", &typeid(double)},   {"epsN", &typeid(double)}, {"epsT", &typeid(double)},
    {"qdeg", &typeid(long)},       {"nodal", &typeid(long)},  {"crel", &typeid(double)}, {"cabs", &typeid(double)},
    {"muD", &typeid(double)},      {"gtol", &typeid(double)}, {"ftol", &typeid(double)}, {"maxFlips", &typeid(long)},
    {"scale", &typeid(double)},    {"dual", &typeid(long)},   {"dualT", &typeid(long)}};

const char *method_name(int m) { return m == FFC_METHOD_NTS ? "nts" : m == FFC_METHOD_MORTAR ? "mortar" : "al"; }

ffc_pair_opts named_pair_opts(const char *fn, const Named &nm, const SceneData &d, ffc_pair_opts o)
{
    const std::string method = nm.str(PO_METHOD, method_name(o.method));
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
        if (!fx.friction) {   // (the fix keeps the scene's other effects)
            std::string e = "ffcFriction";
            if (fx.dynamic) e += " + ffcDynamic";
            if (fx.finite_def) e += " + ffcFiniteDef";
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

// ffcAddPair(C, slaveLabs, masterLabs, method = "al", mu = 0, epsN, epsT = 0,
// qdeg = 4, nodal = 1, crel = 2, cabs = 0): returns the pair's index.
long addPair(const Named &nm, FFScene *const &C, KN<long> *const &sl, KN<long> *const &ml)
{
    const char *fn = "ffcAddPair";
    SceneData &d = need_scene(fn, C);
    KN<long> S = side_labels(fn, "slaveLabs", sl), M = side_labels(fn, "masterLabs", ml);
    need_pair_labels(fn, &S, &M);
    ffc_pair_opts o = named_pair_opts(fn, nm, d, ffc_pair_defaults());
    // the facets, from the mesh as the scene was made
    auto select = [&](const char *arg, const KN<long> &labs, std::vector<long> &F, std::vector<long> &tet) {
        std::vector<long> L(labs.N()), out(3 * d.m.nbe);
        for (long i = 0; i < labs.N(); i++) L[i] = labs[i];
        long bad = -1;
        int st = ffc_surface_select(3, d.m.nbe, d.m.be.data(), d.m.belab.data(), d.m.beopp.data(), d.m.nv,
                                    d.m.X.data(), (int)L.size(), L.data(), d.m.nbe, out.data(), &bad);
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
    };
    std::vector<long> Fs, Fm, tS, tM;
    const long nfs = select("slaveLabs", S, Fs, tS), nfm = select("masterLabs", M, Fm, tM);
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

// the pair index k (argument arg) of the scene; -1 allowed when all is set
int need_pair_index(const char *fn, const SceneData &d, long k, bool all, const char *arg = "pair")
{
    const long np = ffc_scene_npairs(d.s);
    if ((all && k == -1) || (k >= 0 && k < np)) return (int)k;
    std::ostringstream s;
    s << "argument '" << arg << "': " << k << " is not a pair of the scene (" << np << " pair" << (np == 1 ? "" : "s")
      << ": 0.." << np - 1 << (all ? ", or -1 for all" : "") << ")";
    fail(fn, s.str());
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
    fail(fn, "argument 'name': \"" + n + "\" is not an option of a pair (mu, epsN, epsT, qdeg, nodal, crel, cabs, nts, mortar, dual, dualT, muD, gtol, ftol, "
                "maxFlips, scale)");
}

long nPairs(const Named &, FFScene *const &C) { return ffc_scene_npairs(need_scene("ffcPairs", C).s); }

// ffcEffects(C): the scene's effects as bits (1 friction, 2 dynamic, 4 finite deformation)
long sceneEffects(const Named &, FFScene *const &C)
{
    ffc_effects fx;
    ffc_scene_effects(need_scene("ffcEffects", C).s, &fx);
    return fx.friction + 2L * fx.dynamic + 4L * fx.finite_def;
}

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
enum { AS_TANGENT, AS_SYMMETRIC, AS_V, AS_DT, AS_DVDU, AS_N };
basicAC_F0::name_and_type assemble_names[] = {{"tangent", &typeid(string *)},
                                              {"symmetric", &typeid(long)},
                                              {"v", &typeid(KN<double> *)},
                                              {"dt", &typeid(double)},
                                              {"dvdu", &typeid(double)}};

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
    std::vector<long> Ti, Tj;
    std::vector<double> Tv;
    int st;
    for (long cap = K ? 4096 : 0;;) {
        Ti.resize(cap); Tj.resize(cap); Tv.resize(cap);
        std::fill(Rc.begin(), Rc.end(), 0.0);
        st = ffc_scene_assemble(d.s, pu, tangent, Rc.data(), cap, Ti.data(), Tj.data(), Tv.data(), &nt, &bad);
        if (st != FFC_ERR_CAPACITY) break;
        cap = nt;
    }
    if (st) scene_error(fn, st, bad, "the contact assembly");
    R->resize(n);
    for (long i = 0; i < n; i++) (*R)[i] = Rc[i];
    double active = 0;
    ffc_scene_stat(d.s, -1, "active", 0, &active);
    if (!K) return (long)active;
    triplets_to_matrix(fn, n, nt, Ti.data(), Tj.data(), Tv.data(), lower, K);
    return (long)active;
}

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

// ffcPoints(C, u, P, pair = -1): one row per slave point (mortar: per slave node; columns of
// ffc_points: x, y, z, gap, pressure, active, area, master facet, traction
// x, y, z, friction state, dissipation); returns the rows.
long scenePoints(const Named &nm, FFScene *const &C, KN<double> *const &u, KNM<double> *const &P)
{
    const char *fn = "ffcPoints";
    SceneData &d = need_scene(fn, C);
    const int k = need_pair_index(fn, d, nm.integer(0, -1), true);
    const double *pu = need_scene_u(fn, d, u);
    if (!P) fail(fn, "argument 'P': array is not defined");
    const long n = ffc_scene_npoints(d.s, k);
    std::vector<double> rows(n * FFC_POINT_COLS + 1);
    long got = 0, bad = -1;
    int st = ffc_scene_points(d.s, pu, k, n, rows.data(), &got, &bad);
    if (st) scene_error(fn, st, bad, "the points");
    P->resize(n, FFC_POINT_COLS);
    for (long r = 0; r < n; r++)
        for (long c = 0; c < FFC_POINT_COLS; c++) (*P)(r, c) = rows[r * FFC_POINT_COLS + c];
    return n;
}

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
    M->resize(n, 15);
    for (long r = 0; r < n; r++) {
        (*M)(r, 0L) = m[r].body;
        for (long k = 0; k < 3; k++) {
            (*M)(r, 1 + k) = m[r].t[k];
            (*M)(r, 4 + k) = m[r].w[k];
            (*M)(r, 7 + k) = m[r].p[k];
            (*M)(r, 10 + k) = m[r].x[k];
        }
        (*M)(r, 13L) = m[r].amount;
        (*M)(r, 14L) = m[r].tet;
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

// ffcMassSpread(M, spread, T): the interpolation T of the redistributed
// mass T' M T (ffc_mass_spread): the dofs with spread[i] != 0 take the
// mean of their neighbours in M off that set. Returns the spread dofs
// that kept their own row (no neighbour off the set).
long massSpread(Matrice_Creuse<double> *const &M, KN<double> *const &spread, Matrice_Creuse<double> *const &T)
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
    if (!T) fail(fn, "argument 'T': matrix is not defined");
    for (size_t k = 0; k < Mv.size(); k++)
        if (!std::isfinite(Mv[k])) fail(fn, "argument 'M': a non-finite entry");
    const long nm = (long)Mv.size(), cap = n + nm;
    std::vector<long> Ti(cap), Tj(cap);
    std::vector<double> Tv(cap), w(n);
    long nt = 0, kept = 0;
    int st = ffc_mass_spread(n, nm, Mi.data(), Mj.data(), Mv.data(), &(*spread)[0], cap, Ti.data(), Tj.data(),
                             Tv.data(), &nt, &kept, w.data());
    if (st) fail(fn, std::string("the interpolation: ") + ffc_strerror(st));
    triplets_to_matrix(fn, n, nt, Ti.data(), Tj.data(), Tv.data(), false, T);
    return kept;
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
    if (st) scene_error(fn, st, bad, "the linear solve");
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
    if (st < 0) scene_error(fn, st, bad, "the condensed Newton");
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
    if (k == "factorRanks") return in.factor_ranks;
    if (k == "factorSplit") return in.factor_split;
    fail(fn, "argument 'name': \"" + k + "\" is not one of factorizations, columns, solves, backsolves, refinements, keptLU, contactDofs, shift, shiftedDofs, rcond, residual, newtonIterations, evaluations, evaluationsShared, evalTime, fallbacks, condensedDofs, support, ranks, factorMB, factorMBmax, factorTime, columnsTime, backsolveTime, reused, factorRanks, factorSplit");
    return 0;
}

// ffcParallelSolve(A, b, x): A x = b by parallel MUMPS over the ranks of
// FreeFem++-mpi (every rank the same A and b; x on every rank). 0 solved,
// 1 singular (the caller cuts the step, as for a failed UMFPACK solve).
long parallelSolveOwn(Matrice_Creuse<double> *const &A, KN<double> *const &b, KN<double> *const &x, const long &own);
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

void need_nts_scale(const char *fn, SceneData &d, int st, long bad)
{
    if (st == FFC_ERR_VALUE) {
        std::ostringstream s;
        s << "pair " << bad << " (" << d.labels[bad] << "): node-to-surface rows need a scale: give scale = ... in ffcAddPair, or the bulk matrix with ffcBulk(C, K)";
        fail(fn, s.str());
    }
}

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
    if (st) scene_error(fn, st, bad, "the node-to-surface solve");
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

template <class R, class... A>
NamedOp<R, A...> *named(const char *fn, basicAC_F0::name_and_type *names, int n, R (*f)(const Named &, const A &...))
{
    return new NamedOp<R, A...>(fn, names, n, f);
}

void init_scene()
{
    Dcl_Type<FFScene *>(InitP<FFScene>, Destroy<FFScene>);
    zzzfff->Add("ffcScene", atype<FFScene *>());
    typedef FFScene *S;
    typedef KN<double> *V;
    TheOperators->Add("<-", named<S, S, pmesh3>("ffcScene", scene_names, 4, sceneInit));
    Global.Add("ffcAddPair", "(", named<long, S, KN<long> *, KN<long> *>("ffcAddPair", pair_names, PO_N, addPair));
    Global.Add("ffcAddPair", "(", named<long, S, long, long>("ffcAddPair", pair_names, PO_N, addPairL));
    Global.Add("ffcAddPair", "(", named<long, S, long, KN<long> *>("ffcAddPair", pair_names, PO_N, addPairLA));
    Global.Add("ffcAddPair", "(", named<long, S, KN<long> *, long>("ffcAddPair", pair_names, PO_N, addPairAL));
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
    Global.Add("ffcPoints", "(", named<long, S, V, KNM<double> *>("ffcPoints", pair_only_names, 1, scenePoints));
    Global.Add("ffcMultipliers", "(", named<long, S, long, V>("ffcMultipliers", nullptr, 0, sceneMultipliers));
    Global.Add("ffcMultipliers", "(", named<long, S, long, V, V>("ffcMultipliers", nullptr, 0, sceneMultipliersT));
    Global.Add("ffcInverted", "(", named<long, S, V>("ffcInverted", nullptr, 0, sceneInverted));
    Global.Add("ffcFixed", "(", named<long, S, V>("ffcFixed", nullptr, 0, sceneFixed));
    Global.Add("ffcSurfaceDofs", "(", named<long, S, V>("ffcSurfaceDofs", nullptr, 0, sceneSurfaceDofs));
    Global.Add("ffcAutoPenalty", "(", named<double, S, long, V, V>("ffcAutoPenalty", nullptr, 0, sceneAutoPenalty));
    Global.Add("ffcFreeMotions", "(", named<long, S, KNM<double> *>("ffcFreeMotions", nullptr, 0, sceneFreeMotions));
    Global.Add("ffcFreeMotions", "(", named<long, S, V, KNM<double> *>("ffcFreeMotions", nullptr, 0, sceneFreeMotionsU));
    Global.Add("ffcFacetSize", "(", named<double, S>("ffcFacetSize", pair_only_names, 1, sceneFacetSize));
    typedef Matrice_Creuse<double> *M;
    Global.Add("ffcBulk", "(", named<long, S, M>("ffcBulk", bulk_names, 1, sceneBulk));
    Global.Add("ffcElastic", "(", named<long, S, M, V, V>("ffcElastic", nullptr, 0, sceneElastic));
    Global.Add("ffcSolve", "(", named<long, S, M, V, V>("ffcSolve", nullptr, 0, sceneSolve));
    Global.Add("ffcNTSSolve", "(", named<long, S, V, V, V, V, V>("ffcNTSSolve", nullptr, 0, sceneNTSSolve));
    Global.Add("ffcNewton", "(", named<long, S, V, V, V>("ffcNewton", newton_names, 11, sceneNewton));
    Global.Add("ffcSolverStat", "(", named<double, S, string *>("ffcSolverStat", nullptr, 0, sceneSolverStat));
    Global.Add("ffcNTSStep", "(", named<long, S>("ffcNTSStep", nullptr, 0, sceneNtsStep));
    Global.Add("ffcRows", "(", named<long, S, V, V, M, M, M, V>("ffcRows", nullptr, 0, sceneRows));
    Global.Add("ffcUpdate", "(", named<long, S, V, V>("ffcUpdate", nullptr, 0, sceneUpdate));
    Global.Add("ffcNTSForce", "(", named<long, S, V>("ffcNTSForce", nullptr, 0, sceneNtsForce));
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
               new OneOperator3_<long, Matrice_Creuse<double> *, KN<double> *, Matrice_Creuse<double> *>(massSpread));
    Global.Add("ffcInverted", "(", new OneOperator2_<long, pmesh3, KN<double> *>(ffcInverted));
    Global.Add("ffcP2Nodes", "(", new OneOperator2_<long, pmesh3, KN<double> *>(ffcP2Nodes));
    Global.Add("ffcSaveVTK", "(", new OneOperator2_<long, string *, KNM<double> *>(ffcSaveVTK));
    Global.Add("ffcWriteColumns", "(",
               new OneOperator4_<long, string *, string *, KNM<double> *, KN<double> *>(ffcWriteColumns));
    Global.Add("ffcNormals", "(",
               new OneOperator4_<long, pmesh3, KN<long> *, KN<double> *, KN<double> *>(ffcNormals));
}

LOADFUNC(init)
