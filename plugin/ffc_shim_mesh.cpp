// ffc_shim_mesh.cpp: mesh and surface arrays, P2 nodes, facet checks, VTK and column output, time and rank helpers, matrix conversions.
#include "ffc_shim.hpp"

namespace ffc_shim {

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
    if (pTh->nt == 0) fail(fn, "argument 'Th': the mesh has no tetrahedra");   // (mesh_arrays reads each face's tetrahedron)
    return *pTh;
}

namespace {

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

} // namespace

// ffcSurface(Th, labs, F): boundary facets of Th whose label is in labs,
// oriented outward, as 3 global vertex indices each, into F; returns their count.
long ffcSurface(pmesh3 const &pTh, KN<long> *const &labs, KN<long> *const &F)
{
    const char *fn = "ffcSurface";
    const Mesh3 &Th = need_mesh(fn, pTh);
    if (!F) fail(fn, "argument 'F': array is not defined");
    return select_surface(fn, "labs", Th, labs, F);
}

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

// ffcMeshQuality(Th): the lowest mean ratio of Th's tetrahedra (1 regular,
// 0 flat); ffcMeshQuality(Th, q): how many lie below q.
namespace {

void meshQuality(const char *fn, pmesh3 const &pTh, double q, double *worst, long *below)
{
    const Mesh3 &Th = need_mesh(fn, pTh);
    MeshArrays m;
    mesh_arrays(Th, m);
    long bad = -1;
    const int st = ffc_mesh_quality(m.nt, m.T.data(), m.nv, m.X.data(), q, worst, &bad, below);
    if (st) fail(fn, "argument 'Th': tetrahedron " + std::to_string(bad) + ": " + ffc_strerror(st));
}

} // namespace
double ffcMeshQuality(pmesh3 const &pTh)
{
    double worst;
    long below;
    meshQuality("ffcMeshQuality", pTh, 0.0, &worst, &below);
    return worst;
}
long ffcMeshQualityBelow(pmesh3 const &pTh, double const &q)
{
    if (!(q >= 0.0 && q <= 1.0)) fail("ffcMeshQuality", "argument 'q': " + num(q) + " is not a mean ratio in [0, 1]");
    double worst;
    long below;
    meshQuality("ffcMeshQuality", pTh, q, &worst, &below);
    return below;
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
namespace {

double rankReduce(const char *fn, double x, int op)
{
    double v = x;
    const int st = ffc_mpi_allreduce(&v, 1, op);
    if (st) fail(fn, ffc_strerror(st));
    return v;
}

} // namespace
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
double ffcRankMax(double x) { return rankReduce("ffcRankMax", x, 1); }
long ffcBarrier() { return ffc_mpi_barrier(); }
double ffcPeakMB() { return ffc_peak_mb(); }

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
                        Matrice_Creuse<double> *K, const char *what)
{
    // (work arrays left unfilled: ffc_triplets_sum writes before it reads)
    const size_t m = (size_t)(nt > 0 ? nt : 1);
    std::unique_ptr<long[]> Ci(new long[m]), Cj(new long[m]), rp(new long[n + 1]), wk(new long[n]);
    std::unique_ptr<double[]> Cv(new double[m]);
    const long nz = ffc_triplets_sum(n, nt, Ti, Tj, Tv, Ci.get(), Cj.get(), Cv.get(), rp.get(), wk.get());
    if (nz < 0) fail(fn, std::string(what) + ": " + ffc_strerror((int)nz));
    long nk = 0;   // (the entries kept: all, or the lower triangle's)
    for (long t = 0; t < nz; t++)
        if (!lower || Ci[t] >= Cj[t]) { Ci[nk] = Ci[t]; Cj[nk] = Cj[t]; Cv[nk] = Cv[t]; nk++; }
    set_matrix(n, nk, Ci.get(), Cj.get(), Cv.get(), lower, K);
}

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

} // namespace ffc_shim
