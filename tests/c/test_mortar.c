/* test_mortar.c: segment-to-segment integration: polygon clipping against
 * an independent construction, segment coverage, the dual basis, the
 * consistent loads of a uniform pressure through non-matching meshes, and
 * the assembled tangent of segment links against central differences. */
#include "ffc_test.h"

/* ------------------------------------------------------------- clipping */
static double shoelace(int n, const double p[][2])
{
    double a = 0;
    for (int i = 0; i < n; i++) a += p[i][0] * p[(i + 1) % n][1] - p[(i + 1) % n][0] * p[i][1];
    return 0.5 * a;
}

static int inside_tri(const double t[3][2], const double p[2])
{
    for (int i = 0; i < 3; i++) {
        const double *a = t[i], *b = t[(i + 1) % 3];
        if ((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]) < 0) return 0;
    }
    return 1;
}

/* The intersection of two triangles built another way: the candidate
 * vertices (each triangle's vertices inside the other, every crossing of
 * two edges), sorted by angle around their mean; its area. */
static double independent_area(const double a[3][2], const double b[3][2])
{
    double v[32][2], c[2] = {0, 0};
    int n = 0;
    for (int i = 0; i < 3; i++) {
        if (inside_tri(b, a[i])) { v[n][0] = a[i][0]; v[n][1] = a[i][1]; n++; }
        if (inside_tri(a, b[i])) { v[n][0] = b[i][0]; v[n][1] = b[i][1]; n++; }
    }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            const double *p = a[i], *q = a[(i + 1) % 3], *r = b[j], *s = b[(j + 1) % 3];
            const double d1[2] = {q[0] - p[0], q[1] - p[1]}, d2[2] = {s[0] - r[0], s[1] - r[1]};
            const double den = d1[0] * d2[1] - d1[1] * d2[0];
            if (fabs(den) < 1e-300) continue;
            const double t = ((r[0] - p[0]) * d2[1] - (r[1] - p[1]) * d2[0]) / den;
            const double u = ((r[0] - p[0]) * d1[1] - (r[1] - p[1]) * d1[0]) / den;
            if (t < 0 || t > 1 || u < 0 || u > 1) continue;
            v[n][0] = p[0] + t * d1[0];
            v[n][1] = p[1] + t * d1[1];
            n++;
        }
    if (n < 3) return 0.0;
    for (int i = 0; i < n; i++) { c[0] += v[i][0] / n; c[1] += v[i][1] / n; }
    for (int i = 1; i < n; i++) /* insertion sort by angle */
        for (int j = i; j > 0 && atan2(v[j][1] - c[1], v[j][0] - c[0]) < atan2(v[j - 1][1] - c[1], v[j - 1][0] - c[0]);
             j--) {
            double t0 = v[j][0], t1 = v[j][1];
            v[j][0] = v[j - 1][0]; v[j][1] = v[j - 1][1];
            v[j - 1][0] = t0; v[j - 1][1] = t1;
        }
    return shoelace(n, (const double(*)[2])v);
}

static void random_tri(uint64_t *s, double t[3][2])
{
    do {
        for (int i = 0; i < 3; i++) { t[i][0] = test_rand(s, 0, 1); t[i][1] = test_rand(s, 0, 1); }
    } while (fabs(shoelace(3, (const double(*)[2])t)) < 1e-3);
    if (shoelace(3, (const double(*)[2])t) < 0) {
        double x = t[1][0], y = t[1][1];
        t[1][0] = t[2][0]; t[1][1] = t[2][1];
        t[2][0] = x; t[2][1] = y;
    }
}

/* random overlapping triangles: the clipped area against the independent
 * construction (round-off: 1e-13 of the unit box), convex and inside both */
static void test_clip_random(void **state)
{
    (void)state;
    uint64_t s = 7;
    int overlapping = 0;
    for (int k = 0; k < 2000; k++) {
        double a[3][2], b[3][2], out[8][2];
        random_tri(&s, a);
        random_tri(&s, b);
        const int n = ffc_clip_polygon(3, (const double(*)[2])a, 3, (const double(*)[2])b, 8, out);
        assert_true(n >= 0);
        const double A = n ? shoelace(n, (const double(*)[2])out) : 0.0, B = independent_area(a, b);
        assert_close(A, B, 1e-13);
        overlapping += n > 0;
        for (int i = 0; i < n; i++) {
            const double *p = out[i], *q = out[(i + 1) % n], *r = out[(i + 2) % n];
            assert_true((q[0] - p[0]) * (r[1] - q[1]) - (q[1] - p[1]) * (r[0] - q[0]) > -1e-13); /* convex, ccw */
        }
    }
    assert_true(overlapping > 500);
    /* a triangle inside the other: itself; disjoint: nothing */
    const double big[3][2] = {{-1, -1}, {3, -1}, {-1, 3}}, small[3][2] = {{0, 0}, {1, 0}, {0, 1}};
    const double far[3][2] = {{5, 5}, {6, 5}, {5, 6}};
    double out[8][2];
    assert_int_equal(ffc_clip_polygon(3, small, 3, big, 8, out), 3);
    assert_close(shoelace(3, (const double(*)[2])out), 0.5, 1e-15);
    assert_int_equal(ffc_clip_polygon(3, small, 3, far, 8, out), 0);
    /* sharing an edge only: no overlap */
    const double nb[3][2] = {{1, 0}, {1, 1}, {0, 1}};
    assert_int_equal(ffc_clip_polygon(3, small, 3, nb, 8, out), 0);
}

static void test_clip_bad_input(void **state)
{
    (void)state;
    const double t[3][2] = {{0, 0}, {1, 0}, {0, 1}}, cw[3][2] = {{0, 0}, {0, 1}, {1, 0}};
    const double nan_t[3][2] = {{0, 0}, {NAN, 0}, {0, 1}};
    double out[8][2];
    assert_int_equal(ffc_clip_polygon(3, NULL, 3, t, 8, out), FFC_ERR_NULL);
    assert_int_equal(ffc_clip_polygon(2, t, 3, t, 8, out), FFC_ERR_SIZE);
    assert_int_equal(ffc_clip_polygon(3, t, 3, t, 5, out), FFC_ERR_CAPACITY);
    assert_int_equal(ffc_clip_polygon(3, t, 3, cw, 8, out), FFC_ERR_DEGENERATE);
    assert_int_equal(ffc_clip_polygon(3, t, 3, nan_t, 8, out), FFC_ERR_NONFINITE);
    double xi[4][2], w[4], cov;
    const double Xs[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, Xm[3][3] = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}};
    assert_int_equal(ffc_mortar_segment(7, Xs, Xm, 4, xi, w, 0, NULL, NULL, NULL, &cov), FFC_ERR_QUAD);
    assert_int_equal(ffc_mortar_segment(2, Xs, Xm, 2, xi, w, 0, NULL, NULL, NULL, &cov), FFC_ERR_CAPACITY);
    assert_int_equal(ffc_mortar_segment(2, Xs, Xm, 4, xi, w, 0, NULL, NULL, NULL, &cov), 3);
    assert_close(cov, 0.5, 1e-15);
}

/* The segment's motion: for a fixed integrand F(xi) (degree 2: the
 * segment rule of degree 2 integrates it exactly), I(u) = sum_q w_q
 * F(xi_q) changes only through the segment, and its derivative is the
 * boundary term sum_b F(exi_b) edv_b.  Central differences (h = 1e-6) of
 * I over the 18 nodal coordinates, for random facing facet pairs that
 * overlap partly (edges of both kinds), to 1e-8 relative (the rules are
 * exact: the differences' truncation and round-off only). */
static double poly2(const double xi[2]) { return 1 + 2 * xi[0] + xi[1] * xi[1] + xi[0] * xi[1]; }

static void test_segment_motion(void **state)
{
    (void)state;
    uint64_t s = 99;
    int tried = 0;
    for (int k = 0; k < 40; k++) {
        double X[6][3];
        const double base[6][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 0.2, 0.05}, {0.1, 0.9, 0.02}, {1.1, 0.6, -0.03}};
        for (int a = 0; a < 6; a++)
            for (int i = 0; i < 3; i++) X[a][i] = base[a][i] + test_rand(&s, -0.15, 0.15);
        double xi[96][2], w[96], exi[8][2], edv[8][18], cov;
        long ne;
        int n = ffc_mortar_segment(2, (const double(*)[3])X, (const double(*)[3])(X + 3), 96, xi, w, 8, exi, edv, &ne, &cov);
        assert_true(n >= 0);
        if (n == 0 || ne == 0) continue;
        tried++;
        double scale = 0;
        for (int l = 0; l < 18; l++) {
            double dI = 0, Ip = 0, Im = 0;
            for (long b = 0; b < ne; b++) dI += poly2(exi[b]) * edv[b][l];
            const double h = 1e-6, x0 = X[l / 3][l % 3];
            for (int side = 0; side < 2; side++) {
                X[l / 3][l % 3] = x0 + (side ? -h : h);
                double xi2[96][2], w2[96], c2;
                int n2 = ffc_mortar_segment(2, (const double(*)[3])X, (const double(*)[3])(X + 3), 96, xi2, w2, 0, NULL,
                                            NULL, NULL, &c2);
                assert_true(n2 > 0);
                double I = 0;
                for (int q = 0; q < n2; q++) I += w2[q] * poly2(xi2[q]);
                if (side) Im = I; else Ip = I;
            }
            X[l / 3][l % 3] = x0;
            scale = fmax(scale, fabs(dI));
            assert_close(dI, (Ip - Im) / (2 * h), 1e-8 * fmax(1.0, fabs(dI)));
        }
        assert_true(scale > 1e-3);
    }
    assert_true(tried >= 10);
}

/* ---------------------------------------------------------- flat meshes */
/* An n x n grid of the unit square at height z, each cell cut in two
 * (diagonal alternating with shift), rotated by ang about the square's
 * centre and shrunk by scale; normal up (+z) or down. */
/* an m x m lattice of nodes from v0 over [0.5 -+ scale/2]^2 rotated by ang
 * about its centre, at height z; returns the next free node */
static long lattice(int m, double z, double ang, double scale, long v0, double X[])
{
    long v = v0;
    const double c = cos(ang), s = sin(ang);
    for (int j = 0; j < m; j++)
        for (int i = 0; i < m; i++, v++) {
            const double x = scale * ((double)i / (m - 1) - 0.5), y = scale * ((double)j / (m - 1) - 0.5);
            X[3 * v] = 0.5 + c * x - s * y;
            X[3 * v + 1] = 0.5 + s * x + c * y;
            X[3 * v + 2] = z;
        }
    return v;
}

static long grid(int n, double z, double ang, double scale, int up, int shift, long v0, double X[], long F[])
{
    const long v = lattice(n + 1, z, ang, scale, v0, X);
    long f = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            const long a = v0 + j * (n + 1) + i, b = a + 1, d = a + n + 1, e = d + 1;
            long t[6];
            if ((i + j + shift) % 2) { long u[6] = {a, b, e, a, e, d}; memcpy(t, u, sizeof t); }
            else { long u[6] = {a, b, d, b, e, d}; memcpy(t, u, sizeof t); }
            if (!up)
                for (int k = 0; k < 6; k += 3) { long x = t[k + 1]; t[k + 1] = t[k + 2]; t[k + 2] = x; }
            memcpy(F + 6 * f, t, sizeof t);
            f++;
        }
    return v;
}

/* coverage: the segments of each slave facet of a fine grid over a coarse
 * non-matching grid (all inside it) sum to the facet's area, 1/2 in local
 * coordinates, and so do their weights */
static void test_segment_coverage(void **state)
{
    (void)state;
    enum { NM = 3, NS = 7 };
    static double X[3 * ((NM + 1) * (NM + 1) + (NS + 1) * (NS + 1))];
    static long Fm[6 * NM * NM], Fs[6 * NS * NS];
    const long nv0 = grid(NM, 0.0, 0.0, 1.0, 1, 0, 0, X, Fm);
    grid(NS, 0.0, 0.3, 0.7, 0, 1, nv0, X, Fs);
    for (long f = 0; f < 2 * NS * NS; f++) {
        double Xs[3][3], sum = 0, wsum = 0;
        for (int a = 0; a < 3; a++) memcpy(Xs[a], X + 3 * Fs[3 * f + a], sizeof Xs[a]);
        for (long g = 0; g < 2 * NM * NM; g++) {
            double Xm[3][3], xi[96][2], w[96], cov;
            for (int a = 0; a < 3; a++) memcpy(Xm[a], X + 3 * Fm[3 * g + a], sizeof Xm[a]);
            const int n = ffc_mortar_segment(2, (const double(*)[3])Xs, (const double(*)[3])Xm, 96, xi, w, 0, NULL, NULL, NULL, &cov);
            assert_true(n >= 0);
            sum += cov;
            for (int q = 0; q < n; q++) {
                wsum += w[q];
                assert_true(xi[q][0] >= -1e-14 && xi[q][1] >= -1e-14 && xi[q][0] + xi[q][1] <= 1 + 1e-14);
            }
        }
        assert_close(sum, 0.5, 1e-14);
        assert_close(wsum, 0.5, 1e-14);
    }
}

/* the dual basis: 4 N_a - 1 on a full facet; biorthogonal on a facet
 * covered to 99%; blended with the standard one at 68% (each node's
 * weight sum_q w Phi_a still D_aa); standard below half and for a sliver */
static void test_dual_basis(void **state)
{
    (void)state;
    const double Xs[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const double full[3][3] = {{-1, -1, 1}, {3, -1, 1}, {-1, 3, 1}};
    /* the line x + y / 2 = 0.93 cuts off the corner at (1, 0): 99% covered */
    const double part[3][3] = {{2.43, -3, 1}, {-0.57, 3, 1}, {-5, -5, 1}};
    /* x + y / 2 = 0.6: 68% covered; x + y / 2 = 0.4: 32% */
    const double p70[3][3] = {{2.1, -3, 1}, {-0.9, 3, 1}, {-5, -5, 1}}, p35[3][3] = {{1.9, -3, 1}, {-1.1, 3, 1}, {-5, -5, 1}};
    double xi[96][2], w[96], cov, A[3][3];
    int n = ffc_mortar_segment(2, Xs, full, 96, xi, w, 0, NULL, NULL, NULL, &cov);
    assert_true(n > 0);
    assert_int_equal(ffc_dual_basis(n, (const double(*)[2])xi, w, A), FFC_OK);
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) assert_close(A[a][b], a == b ? 3.0 : -1.0, 1e-12);
    n = ffc_mortar_segment(2, Xs, part, 96, xi, w, 0, NULL, NULL, NULL, &cov);
    assert_close(cov, 0.5 - 0.0049, 1e-12);
    assert_int_equal(ffc_dual_basis(n, (const double(*)[2])xi, w, A), FFC_OK);
    double D[3] = {0}, M[3][3] = {{0}};
    for (int q = 0; q < n; q++) {
        const double N[3] = {1 - xi[q][0] - xi[q][1], xi[q][0], xi[q][1]};
        for (int a = 0; a < 3; a++) {
            const double Phi = A[a][0] * N[0] + A[a][1] * N[1] + A[a][2] * N[2];
            D[a] += w[q] * N[a];
            for (int b = 0; b < 3; b++) M[a][b] += w[q] * Phi * N[b];
        }
    }
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) assert_close(M[a][b], a == b ? D[a] : 0.0, 1e-14);
    for (int k = 0; k < 2; k++) {
        n = ffc_mortar_segment(2, Xs, k ? p35 : p70, 96, xi, w, 0, NULL, NULL, NULL, &cov);
        assert_close(2 * cov, k ? 0.32 : 0.68, 1e-12);
        assert_int_equal(ffc_dual_basis(n, (const double(*)[2])xi, w, A), FFC_OK);
        double Wd[3] = {0}, Dd[3] = {0}, off = 0;
        for (int q = 0; q < n; q++) {
            const double N[3] = {1 - xi[q][0] - xi[q][1], xi[q][0], xi[q][1]};
            for (int a = 0; a < 3; a++) {
                Dd[a] += w[q] * N[a];
                Wd[a] += w[q] * (A[a][0] * N[0] + A[a][1] * N[1] + A[a][2] * N[2]);
            }
        }
        for (int a = 0; a < 3; a++) {
            assert_close(Wd[a], Dd[a], 1e-14);
            for (int b = 0; b < 3; b++) off = fmax(off, fabs(A[a][b] - (a == b)));
        }
        if (k) assert_true(off == 0.0); /* below half: standard */
        else assert_true(off > 0.1);    /* blended */
    }
    const double sliver[1][2] = {{0.5, 0.5}}, ws[1] = {0.1};
    assert_int_equal(ffc_dual_basis(1, sliver, ws, A), FFC_OK);
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) assert_close(A[a][b], a == b, 0.0);
}

/* ------------------------------------- uniform pressure through a mesh */
/* Two coplanar non-matching grids, the slave's multipliers all p and no
 * gap: the assembled residual on the master's nodes is the consistent
 * load of a uniform pressure, p times the integral of each master shape
 * function over the master square (all of it covered) computed
 * independently as p A / 3 per facet vertex, to round-off; on the
 * slave's, -p A / 3 likewise (dual and standard multipliers).  The same
 * with the pointwise links of a facet rule (ffc_search) misses: the
 * master shape functions kink inside slave facets. */
static void test_uniform_pressure(void **state)
{
    (void)state;
    enum { NM = 3, NS = 8, NVM = (NM + 1) * (NM + 1), NV = NVM + (NS + 1) * (NS + 1) };
    static double X[3 * NV], u[3 * NV], R[3 * NV], lam[NV], ref[3 * NV];
    static long Fm[6 * NM * NM], Fs[6 * NS * NS];
    grid(NM, 0.0, 0.0, 1.0, 1, 0, 0, X, Fm);
    grid(NS, 0.0, 0.0, 1.0, 0, 1, NVM, X, Fs);
    /* the slave square slightly larger than the master one would leave its
     * rim uncovered; equal squares, non-matching inside */
    const double p = 2.5;
    memset(ref, 0, sizeof ref);
    for (long f = 0; f < 2 * NM * NM; f++)
        for (int a = 0; a < 3; a++) ref[3 * Fm[3 * f + a] + 2] = 0; /* set below */
    for (int side = 0; side < 2; side++) {
        const long nf = side ? 2 * NS * NS : 2 * NM * NM, *F = side ? Fs : Fm;
        for (long f = 0; f < nf; f++) {
            const double *x0 = X + 3 * F[3 * f], *x1 = X + 3 * F[3 * f + 1], *x2 = X + 3 * F[3 * f + 2];
            const double A = 0.5 * fabs((x1[0] - x0[0]) * (x2[1] - x0[1]) - (x1[1] - x0[1]) * (x2[0] - x0[0]));
            for (int a = 0; a < 3; a++) ref[3 * F[3 * f + a] + 2] += (side ? -1.0 : 1.0) * p * A / 3.0;
        }
    }
    /* sign: the pressure pushes the slave (above, normal down) up and the master down */
    ffc_tree *t;
    assert_int_equal(ffc_tree_build(3, 2 * NM * NM, Fm, NV, X, &t), FFC_OK);
    static ffc_link L[20000];
    long need;
    const int nl = ffc_mortar_search(t, 2 * NS * NS, Fs, NV, X, 2, NULL, 20000, L, &need);
    assert_true(nl > 0);
    assert_int_equal(need, nl);
    static double dual[9 * 2 * NS * NS];
    for (long a = 0; a < nl;) {
        long b = a;
        while (b < nl && L[b].sf == L[a].sf) b++;
        double xi[512][2], w[512], A[3][3];
        for (long k = a; k < b; k++) { xi[k - a][0] = L[k].xs[0]; xi[k - a][1] = L[k].xs[1]; w[k - a] = L[k].w; }
        assert_int_equal(ffc_dual_basis(b - a, (const double(*)[2])xi, w, A), FFC_OK);
        memcpy(dual + 9 * L[a].sf, A, sizeof A);
        a = b;
    }
    for (long v = NVM; v < NV; v++) lam[v] = p;
    ffc_pair P = {3, 2 * NS * NS, Fs, 3, 2 * NM * NM, Fm, NV, X, u, NULL, NULL, NULL};
    ffc_effects fx = {0, 0, 0};
    for (int d = 0; d <= 1; d++) {
        ffc_law law = {1e3, 1, 0, 0.0, 0.0, 0.0, 0.0, NULL, d ? dual : NULL, 0, NULL, 0, NULL, NULL, NULL};
        long nt, bad;
        memset(R, 0, sizeof R);
        assert_int_equal(ffc_assemble(&fx, &P, 0, nl, L, lam, NULL, &law, R, 0, NULL, NULL, NULL, &nt, NULL, &bad),
                         FFC_OK);
        for (long k = 0; k < 3 * NV; k++) assert_close(R[k], ref[k], 1e-14 * p);
    }
    /* the pointwise rule of degree 2 on the same meshes */
    enum { NQ = 3, NLQ = 2 * NS * NS * NQ };
    static ffc_link Lq[NLQ];
    assert_int_equal(ffc_search(t, 3, 2 * NS * NS, Fs, NV, X, 2, NULL, NLQ, Lq), NLQ);
    ffc_law law = {1e3, 1, 0, 0.0, 0.0, 0.0, 0.0, NULL, NULL, 0, NULL, 0, NULL, NULL, NULL};
    long nt, bad;
    memset(R, 0, sizeof R);
    assert_int_equal(ffc_assemble(&fx, &P, 2, NLQ, Lq, lam, NULL, &law, R, 0, NULL, NULL, NULL, &nt, NULL, &bad), FFC_OK);
    double err = 0;
    for (long k = 0; k < 3 * NVM; k++) err = fmax(err, fabs(R[k] - ref[k]));
    assert_true(err > 1e-3 * p / (NM * NM)); /* the facet rule misses the master loads */
    ffc_tree_free(t);
}

/* ------------------------------------------------- assembled tangents */
enum { TNV = 41, TNFM = 32, TNFS = 18, TCAP = 400000 };

typedef struct {
    double X[TNV * 3], u[TNV * 3], up[TNV * 3];
    long Fm[TNFM * 3], Fs[TNFS * 3];
    ffc_link L[4000];
    long nl;
    double lam[TNV], lam_t[TNV * 3], dual[9 * TNFS];
    ffc_pair P;
} mscene;

static void mscene_make(mscene *a, uint64_t *s)
{
    test_pair_scene(a->X, a->Fm, a->Fs);
    double x[TNV * 3];
    for (int i = 0; i < TNV * 3; i++) {
        a->u[i] = test_rand(s, -0.002, 0.002);
        a->up[i] = a->u[i] - test_rand(s, -0.003, 0.003);
    }
    for (int v = 25; v < TNV; v++) a->u[3 * v + 2] -= 0.004;
    for (int i = 0; i < TNV * 3; i++) x[i] = a->X[i] + a->u[i];
    ffc_tree *t;
    assert_int_equal(ffc_tree_build(3, TNFM, a->Fm, TNV, x, &t), FFC_OK);
    long need;
    const int nl = ffc_mortar_search(t, TNFS, a->Fs, TNV, x, 2, NULL, 4000, a->L, &need);
    assert_true(nl > TNFS * 3); /* more points than the facet rule: the segments */
    a->nl = nl;
    ffc_tree_free(t);
    for (long f = 0; f < 9 * TNFS; f++) a->dual[f] = f % 4 == 0; /* overwritten for facets with links */
    for (long b0 = 0; b0 < nl;) {
        long b = b0;
        while (b < nl && a->L[b].sf == a->L[b0].sf) b++;
        double xi[1024][2], w[1024], A[3][3];
        for (long k = b0; k < b; k++) { xi[k - b0][0] = a->L[k].xs[0]; xi[k - b0][1] = a->L[k].xs[1]; w[k - b0] = a->L[k].w; }
        assert_int_equal(ffc_dual_basis(b - b0, (const double(*)[2])xi, w, A), FFC_OK);
        memcpy(a->dual + 9 * a->L[b0].sf, A, sizeof A);
        b0 = b;
    }
    for (int k = 0; k < TNV; k++) a->lam[k] = k < 25 ? 0.0 : test_rand(s, 0.0, 0.3);
    for (int k = 0; k < TNV * 3; k++) a->lam_t[k] = test_rand(s, -0.05, 0.05);
    ffc_pair P = {3, TNFS, a->Fs, 3, TNFM, a->Fm, TNV, a->X, a->u, a->up, NULL, NULL};
    a->P = P;
}

/* Central differences (h = 1e-7 against displacements ~1e-3) of the
 * assembled residual of segment links at fixed segments, against the
 * tangent: relative 1e-6 (the differences' truncation and round-off) */
static void check_tangent(mscene *a, const ffc_effects *fx, const ffc_law *law, int regime)
{
    static double K[TNV * 3][TNV * 3];
    long *Ti = malloc(TCAP * sizeof *Ti), *Tj = malloc(TCAP * sizeof *Tj), nt, bad;
    double *Tv = malloc(TCAP * sizeof *Tv), R[TNV * 3] = {0};
    ffc_stats st;
    assert_int_equal(ffc_assemble(fx, &a->P, 0, a->nl, a->L, a->lam, a->lam_t, law, R, TCAP, Ti, Tj, Tv, &nt, &st, &bad),
                     FFC_OK);
    memset(K, 0, sizeof K);
    for (long k = 0; k < nt; k++) K[Ti[k]][Tj[k]] += Tv[k];
    free(Ti); free(Tj); free(Tv);
    if (regime == FFC_FRIC_OPEN) {
        assert_int_equal(st.active, 0);
        assert_int_equal(nt, 0);
    } else {
        assert_true(st.active > 0);
        if (fx->friction) {
            assert_true((regime == FFC_FRIC_STICK ? st.stick : st.slip) > 0);
            assert_int_equal(regime == FFC_FRIC_STICK ? st.slip : st.stick, 0);
        }
    }
    const double h = 1e-7;
    double err = 0, scale = 0;
    for (int l = 0; l < TNV * 3; l++) {
        double Rp[TNV * 3] = {0}, Rm[TNV * 3] = {0}, u0 = a->u[l];
        ffc_stats sp, sm;
        a->u[l] = u0 + h;
        assert_int_equal(ffc_assemble(fx, &a->P, 0, a->nl, a->L, a->lam, a->lam_t, law, Rp, 0, NULL, NULL, NULL, &nt,
                                      &sp, &bad), FFC_OK);
        a->u[l] = u0 - h;
        assert_int_equal(ffc_assemble(fx, &a->P, 0, a->nl, a->L, a->lam, a->lam_t, law, Rm, 0, NULL, NULL, NULL, &nt,
                                      &sm, &bad), FFC_OK);
        a->u[l] = u0;
        assert_int_equal(sp.active, st.active);
        assert_int_equal(sm.active, st.active);
        for (int k = 0; k < TNV * 3; k++) {
            err = fmax(err, fabs((Rp[k] - Rm[k]) / (2 * h) - K[k][l]));
            scale = fmax(scale, fabs(K[k][l]));
            if (regime == FFC_FRIC_OPEN) assert_true(Rp[k] == 0.0 && Rm[k] == 0.0);
        }
    }
    if (!(err <= 1e-6 * scale))
        fail_msg("segment tangent error %.3g of scale %.3g (friction %d, finite %d, dual %d)", err, scale, fx->friction,
                 fx->finite_def, law->dual != NULL);
}

static void test_segment_tangent(void **state)
{
    (void)state;
    uint64_t s = 41;
    mscene *a = malloc(sizeof *a);
    mscene_make(a, &s);
    for (int finite = 0; finite <= 1; finite++)
        for (int d = 0; d <= 1; d++) {
            const double *dual = d ? a->dual : NULL;
            ffc_effects fr = {0, 0, finite}, fc = {1, 0, finite};
            ffc_law normal = {60, 1, 0, 0.0, 0.0, 0.0, 0.0, NULL, dual, 0, NULL, 0, NULL, NULL, NULL};
            check_tangent(a, &fr, &normal, FFC_FRIC_STICK);
            ffc_law stick = {60, 1, 0, 1e6, 5.0, 0.0, 0.0, NULL, dual, 0, NULL, 0, NULL, NULL, NULL};
            check_tangent(a, &fc, &stick, FFC_FRIC_STICK);
            ffc_law slip = {60, 1, 0, 0.3, 2000.0, 0.0, 0.0, NULL, dual, 0, NULL, 0, NULL, NULL, NULL};
            check_tangent(a, &fc, &slip, FFC_FRIC_SLIP);
        }
    /* separated: the slave lifted off, no multipliers: nothing, exactly */
    for (int v = 25; v < TNV; v++) a->u[3 * v + 2] += 0.05;
    for (int k = 0; k < TNV; k++) a->lam[k] = 0.0;
    ffc_effects fc = {1, 0, 0};
    ffc_law stick = {60, 1, 0, 1e6, 5.0, 0.0, 0.0, NULL, a->dual, 0, NULL, 0, NULL, NULL, NULL};
    check_tangent(a, &fc, &stick, FFC_FRIC_OPEN);
    free(a);
}

/* Segments that follow the surfaces: the facet pairs fixed (ffc_mortar_pairs
 * at u), their segments, dual basis and links taken again at every
 * perturbed u (ffc_mortar_links), against the tangent with the moving-edge
 * terms (law.edge).  A kinked master (its nodes moved in every direction)
 * under a fully covered slave surface pressed in unevenly; frictionless,
 * all stick and all slip; small strain and finite deformation.  Central
 * differences, h = 1e-7: relative 1e-6.  Without the edge terms the same
 * differences miss by more than 1e-5 of the tangent (asserted too: the terms
 * are not vacuous; measured: 3e-10 to 1e-9 with them, 1.6e-3 to 2.5e-3
 * without). */
enum { RM = 3, RS = 4, RVM = (RM + 1) * (RM + 1), RV = RVM + (RS + 1) * (RS + 1), RCAP = 400000 };
typedef struct {
    double X[3 * RV], u[3 * RV], up[3 * RV], lam[RV], lam_t[3 * RV], dual[9 * 2 * RS * RS];
    long Fm[6 * RM * RM], Fs[6 * RS * RS], pairs[2 * 400];
    long np;
    ffc_link L[20000];
    ffc_mortar_edge E[4000];
    long nl, ne;
} rscene;

/* the segments of the pairs at a->u, their dual basis */
static void rs_link(rscene *a)
{
    double x[3 * RV];
    for (int i = 0; i < 3 * RV; i++) x[i] = a->X[i] + a->u[i];
    long ln, en;
    const int n = ffc_mortar_links(3, 2 * RS * RS, a->Fs, 2 * RM * RM, a->Fm, RV, x, 2, a->np, a->pairs, 20000, a->L, &ln,
                                   4000, a->E, &en);
    assert_true(n > 0);
    a->nl = ln;
    a->ne = en;
    for (long f = 0; f < 9 * 2 * RS * RS; f++) a->dual[f] = f % 4 == 0;
    for (long i = 0; i < a->nl;) {
        long j = i;
        while (j < a->nl && a->L[j].sf == a->L[i].sf) j++;
        double xi[1024][2], w[1024], A[3][3], cov = 0;
        for (long k = i; k < j; k++) { xi[k - i][0] = a->L[k].xs[0]; xi[k - i][1] = a->L[k].xs[1]; w[k - i] = a->L[k].w; cov += a->L[k].w; }
        assert_close(cov, 0.5, 1e-12); /* every slave facet fully covered */
        assert_int_equal(ffc_dual_basis(j - i, (const double(*)[2])xi, w, A), FFC_OK);
        memcpy(a->dual + 9 * a->L[i].sf, A, sizeof A);
        i = j;
    }
}

static void rs_check(rscene *a, const ffc_effects *fx, ffc_law law, int regime)
{
    static double K[3 * RV][3 * RV], K0[3 * RV][3 * RV];
    long *Ti = malloc(RCAP * sizeof *Ti), *Tj = malloc(RCAP * sizeof *Tj), nt, bad;
    double *Tv = malloc(RCAP * sizeof *Tv), R[3 * RV];
    ffc_pair P = {3, 2 * RS * RS, a->Fs, 3, 2 * RM * RM, a->Fm, RV, a->X, a->u, a->up, NULL, NULL};
    rs_link(a);
    law.dual = a->dual;
    ffc_stats st;
    for (int with = 0; with < 2; with++) {
        law.nedge = with ? a->ne : 0;
        law.edge = a->E;
        memset(R, 0, sizeof R);
        assert_int_equal(ffc_assemble(fx, &P, 0, a->nl, a->L, a->lam, a->lam_t, &law, R, RCAP, Ti, Tj, Tv, &nt, &st, &bad),
                         FFC_OK);
        double (*M)[3 * RV] = with ? K : K0;
        memset(M, 0, sizeof K);
        for (long k = 0; k < nt; k++) M[Ti[k]][Tj[k]] += Tv[k];
    }
    assert_true(st.active > 0);
    if (fx->friction) {
        assert_true((regime == FFC_FRIC_STICK ? st.stick : st.slip) > 0);
        assert_int_equal(regime == FFC_FRIC_STICK ? st.slip : st.stick, 0);
    }
    law.nedge = 0;
    const double h = 1e-7;
    double err = 0, err0 = 0, scale = 0;
    for (int l = 0; l < 3 * RV; l++) {
        double Rp[3 * RV], Rm[3 * RV];
        const double u0 = a->u[l];
        for (int side = 0; side < 2; side++) {
            a->u[l] = u0 + (side ? -h : h);
            rs_link(a);
            double *out = side ? Rm : Rp;
            memset(out, 0, sizeof Rp);
            ffc_stats s2;
            assert_int_equal(ffc_assemble(fx, &P, 0, a->nl, a->L, a->lam, a->lam_t, &law, out, 0, NULL, NULL, NULL, &nt,
                                          &s2, &bad), FFC_OK);
            assert_int_equal(s2.active, st.active);
        }
        a->u[l] = u0;
        for (int k = 0; k < 3 * RV; k++) {
            const double fd = (Rp[k] - Rm[k]) / (2 * h);
            err = fmax(err, fabs(fd - K[k][l]));
            err0 = fmax(err0, fabs(fd - K0[k][l]));
            scale = fmax(scale, fabs(K[k][l]));
        }
    }
    rs_link(a);
    free(Ti); free(Tj); free(Tv);
    if (!(err <= 1e-6 * scale))
        fail_msg("segments that follow: tangent error %.3g of scale %.3g (friction %d, finite %d, regime %d)", err, scale,
                 fx->friction, fx->finite_def, regime);
    if (!(err0 >= 1e-5 * scale))
        fail_msg("without the edge terms the error is only %.3g of scale %.3g: the case does not test them", err0, scale);
}

static void test_resegmented_tangent(void **state)
{
    (void)state;
    rscene *a = calloc(1, sizeof *a);
    grid(RM, 0.0, 0.0, 1.0, 1, 0, 0, a->X, a->Fm);
    grid(RS, 0.0, 0.35, 0.7, 0, 1, RVM, a->X, a->Fs);
    uint64_t s = 77;
    for (long v = 0; v < RV; v++) {
        a->u[3 * v] = test_rand(&s, -0.01, 0.01);
        a->u[3 * v + 1] = test_rand(&s, -0.01, 0.01);
        a->u[3 * v + 2] = v < RVM ? test_rand(&s, -0.01, 0.01) : test_rand(&s, -0.014, -0.01); /* pressed in */
        a->lam[v] = v < RVM ? 0.0 : test_rand(&s, 5.0, 6.0);
        for (int i = 0; i < 3; i++) {
            a->up[3 * v + i] = a->u[3 * v + i] - test_rand(&s, -0.003, 0.003);
            a->lam_t[3 * v + i] = test_rand(&s, -0.05, 0.05);
        }
    }
    double x[3 * RV];
    for (int i = 0; i < 3 * RV; i++) x[i] = a->X[i] + a->u[i];
    ffc_tree *t;
    assert_int_equal(ffc_tree_build(3, 2 * RM * RM, a->Fm, RV, x, &t), FFC_OK);
    long need;
    const int np = ffc_mortar_pairs(t, 2 * RS * RS, a->Fs, RV, x, NULL, 400, a->pairs, &need);
    ffc_tree_free(t);
    assert_true(np > 2 * RS * RS);
    a->np = np;
    for (int finite = 0; finite <= 1; finite++) {
        ffc_effects fr = {0, 0, finite}, fc = {1, 0, finite};
        ffc_law normal = {1e3, 1, 0, 0.0, 0.0, 0.0, 0.0, NULL, NULL, 0, NULL, 0, NULL, NULL, NULL};
        rs_check(a, &fr, normal, FFC_FRIC_STICK);
        ffc_law stick = {1e3, 1, 0, 1e6, 50.0, 0.0, 0.0, NULL, NULL, 0, NULL, 0, NULL, NULL, NULL};
        rs_check(a, &fc, stick, FFC_FRIC_STICK);
        ffc_law slip = {1e3, 1, 0, 0.3, 2e4, 0.0, 0.0, NULL, NULL, 0, NULL, 0, NULL, NULL, NULL};
        rs_check(a, &fc, slip, FFC_FRIC_SLIP);
    }
    free(a);
}

/* a rigid translation changes no weighted gap: the frictionless tangent
 * (small strain) times a translation is zero, and the residual's slave
 * and master forces balance */
static void test_translation(void **state)
{
    (void)state;
    uint64_t s = 43;
    mscene *a = malloc(sizeof *a);
    mscene_make(a, &s);
    static double K[TNV * 3][TNV * 3];
    long *Ti = malloc(TCAP * sizeof *Ti), *Tj = malloc(TCAP * sizeof *Tj), nt, bad;
    double *Tv = malloc(TCAP * sizeof *Tv), R[TNV * 3] = {0};
    ffc_effects fx = {0, 0, 0};
    ffc_law law = {60, 1, 0, 0.0, 0.0, 0.0, 0.0, NULL, a->dual, 0, NULL, 0, NULL, NULL, NULL};
    assert_int_equal(ffc_assemble(&fx, &a->P, 0, a->nl, a->L, a->lam, NULL, &law, R, TCAP, Ti, Tj, Tv, &nt, NULL, &bad),
                     FFC_OK);
    memset(K, 0, sizeof K);
    for (long k = 0; k < nt; k++) K[Ti[k]][Tj[k]] += Tv[k];
    double scale = 0, tot[3] = {0, 0, 0}, rs = 0;
    for (int i = 0; i < 3 * TNV; i++) {
        tot[i % 3] += R[i];
        rs = fmax(rs, fabs(R[i]));
        for (int j = 0; j < 3 * TNV; j++) scale = fmax(scale, fabs(K[i][j]));
    }
    assert_true(rs > 0);
    for (int c = 0; c < 3; c++) {
        assert_close(tot[c], 0.0, 1e-13 * rs * TNV);
        for (int i = 0; i < 3 * TNV; i++) {
            double Kt = 0;
            for (int v = 0; v < TNV; v++) Kt += K[i][3 * v + c];
            assert_close(Kt, 0.0, 1e-12 * scale);
        }
    }
    free(Ti); free(Tj); free(Tv);
    free(a);
}

static void test_search_bad_input(void **state)
{
    (void)state;
    uint64_t s = 5;
    mscene *a = malloc(sizeof *a);
    mscene_make(a, &s);
    ffc_tree *t;
    assert_int_equal(ffc_tree_build(3, TNFM, a->Fm, TNV, a->X, &t), FFC_OK);
    long need = -1;
    assert_int_equal(ffc_mortar_search(t, TNFS, a->Fs, TNV, a->X, 2, NULL, 3, a->L, &need), FFC_ERR_CAPACITY);
    assert_true(need > 3);
    assert_int_equal(ffc_mortar_search(t, TNFS, a->Fs, TNV, a->X, 2, NULL, need, a->L, &need), need);
    assert_int_equal(ffc_mortar_search(t, TNFS, a->Fs, TNV, a->X, 9, NULL, 4000, a->L, &need), FFC_ERR_QUAD);
    assert_int_equal(ffc_mortar_search(NULL, TNFS, a->Fs, TNV, a->X, 2, NULL, 4000, a->L, &need), FFC_ERR_NULL);
    long bad_f[TNFS * 3];
    memcpy(bad_f, a->Fs, sizeof bad_f);
    bad_f[4] = TNV;
    assert_int_equal(ffc_mortar_search(t, TNFS, bad_f, TNV, a->X, 2, NULL, 4000, a->L, &need), FFC_ERR_INDEX);
    /* segment links need the nodal law and the qdeg 0 convention */
    ffc_effects fx = {0, 0, 0};
    ffc_law pointwise = {60, 0, 0, 0.0, 0.0, 0.0, 0.0, NULL, NULL, 0, NULL, 0, NULL, NULL, NULL};
    double R[TNV * 3] = {0};
    long nt, bad;
    const int nl = ffc_mortar_search(t, TNFS, a->Fs, TNV, a->X, 2, NULL, 4000, a->L, &need);
    assert_int_equal(ffc_assemble(&fx, &a->P, 0, nl, a->L, a->lam, NULL, &pointwise, R, 0, NULL, NULL, NULL, &nt, NULL,
                                  &bad), FFC_ERR_VALUE);
    ffc_law law = {60, 1, 0, 0.0, 0.0, 0.0, 0.0, NULL, NULL, 0, NULL, 0, NULL, NULL, NULL};
    assert_int_equal(ffc_assemble(&fx, &a->P, 2, nl, a->L, a->lam, NULL, &law, R, 0, NULL, NULL, NULL, &nt, NULL, &bad),
                     FFC_ERR_SIZE);
    a->L[3].w = NAN;
    assert_int_equal(ffc_assemble(&fx, &a->P, 0, nl, a->L, a->lam, NULL, &law, R, 0, NULL, NULL, NULL, &nt, NULL, &bad),
                     FFC_ERR_NONFINITE);
    assert_int_equal(bad, 3);
    a->L[3].w = 0.1;
    a->dual[20] = INFINITY;
    law.dual = a->dual;
    assert_int_equal(ffc_assemble(&fx, &a->P, 0, nl, a->L, a->lam, NULL, &law, R, 0, NULL, NULL, NULL, &nt, NULL, &bad),
                     FFC_ERR_NONFINITE);
    assert_int_equal(bad, 2);
    ffc_tree_free(t);
    free(a);
}

/* a frictionless small-strain scene of nn-node facets with one mortar pair
 * (rule of degree qdeg, eps_n 1e3); *o its options */
static ffc_scene *mortar_scene(int nn, long nv, const double X[], long nfs, const long Fs[], long nfm, const long Fm[],
                               int qdeg, ffc_pair_opts *o)
{
    ffc_effects fx = {0, 0, 0};
    ffc_scene *s;
    assert_int_equal(ffc_scene_create(nn, nv, X, 0, NULL, &fx, &s), FFC_OK);
    *o = ffc_pair_defaults();
    o->method = FFC_METHOD_MORTAR;
    o->qdeg = qdeg;
    o->eps_n = 1e3;
    long bad;
    assert_int_equal(ffc_scene_add_pair(s, nfs, Fs, nfm, Fm, o, &bad), 0);
    return s;
}

/* A mortar pair in a scene: nothing to add before its first search (a
 * dynamic scene evaluates its residual before searching), its links and
 * dual basis from each search, one output row per slave node with the
 * nodal pressure, and the scene's refusal of pointwise multipliers. */
static void test_scene_pair(void **state)
{
    (void)state;
    enum { NM = 3, NS = 4, NVM = (NM + 1) * (NM + 1), NV = NVM + (NS + 1) * (NS + 1) };
    static double X[3 * NV], u[3 * NV], R[3 * NV];
    static long Fm[6 * NM * NM], Fs[6 * NS * NS];
    grid(NM, 0.0, 0.0, 1.0, 1, 0, 0, X, Fm);
    grid(NS, 0.0, 0.35, 0.7, 0, 1, NVM, X, Fs);
    ffc_pair_opts o;
    long bad;
    ffc_scene *s = mortar_scene(3, NV, X, 2 * NS * NS, Fs, 2 * NM * NM, Fm, 2, &o);
    memset(u, 0, sizeof u);
    for (long v = NVM; v < NV; v++) u[3 * v + 2] = -0.001; /* the slave pressed in by 0.001 */
    long nt;
    memset(R, 0, sizeof R);
    assert_int_equal(ffc_scene_assemble(s, u, FFC_TANGENT_NONE, R, 0, NULL, NULL, NULL, &nt, &bad), FFC_OK);
    for (long k = 0; k < 3 * NV; k++) assert_true(R[k] == 0.0); /* no links yet */
    long linked;
    assert_int_equal(ffc_scene_search(s, u, &linked, &bad), FFC_OK);
    assert_true(linked > 2 * NS * NS * 3);
    assert_int_equal(ffc_scene_nlinks(s, 0), linked);
    assert_int_equal(ffc_scene_assemble(s, u, FFC_TANGENT_NONE, R, 0, NULL, NULL, NULL, &nt, &bad), FFC_OK);
    double fz = 0;
    for (long v = NVM; v < NV; v++) fz += R[3 * v + 2];
    /* the penalty pressure eps g = 1 over the slave's area 0.49 pushes it up: -R */
    assert_close(fz, -1e3 * 0.001 * 0.49, 1e-12);
    const long np = ffc_scene_npoints(s, 0, 0);
    assert_int_equal(np, (NS + 1) * (NS + 1));
    double *P = malloc(np * FFC_POINT_COLS * sizeof *P);
    long n;
    assert_int_equal(ffc_scene_points(s, u, 0, 0, np, P, &n, &bad), FFC_OK);
    double area = 0;
    for (long r = 0; r < n; r++) {
        assert_close(P[r * FFC_POINT_COLS + 3], -0.001, 1e-15); /* weighted gap = nodal gap */
        assert_close(P[r * FFC_POINT_COLS + 4], 1.0, 1e-12);    /* nodal pressure eps g */
        area += P[r * FFC_POINT_COLS + 6];
    }
    assert_close(area, 0.49, 1e-14);
    free(P);
    o.nodal = 0;
    assert_int_equal(ffc_scene_add_pair(s, 2 * NS * NS, Fs, 2 * NM * NM, Fm, &o, &bad), FFC_ERR_VALUE);
    ffc_scene_free(s);
}

/* quadratic (6-node) facets over [0.5 -+ scale/2]^2 rotated by ang at
 * height z: a (2n+1)^2 lattice from v0, each cell two triangles, corners
 * first, then the midpoints of edges 0-1, 1-2, 2-0 (ffc_shape's order);
 * up: normals +z.  Returns the next free node. */
static long grid6(int n, double z, double ang, double scale, int up, long v0, double X[], long F[])
{
    const int m = 2 * n + 1;
    const long v = lattice(m, z, ang, scale, v0, X);
    long f = 0;
    for (int cj = 0; cj < n; cj++)
        for (int ci = 0; ci < n; ci++) {
            const int P[2][3][2] = {{{0, 0}, {2, 0}, {2, 2}}, {{0, 0}, {2, 2}, {0, 2}}};
            for (int t = 0; t < 2; t++) {
                int q[3][2];
                for (int a = 0; a < 3; a++) {
                    const int b = up ? a : (3 - a) % 3; /* !up: corners 0, 2, 1 */
                    q[a][0] = 2 * ci + P[t][b][0];
                    q[a][1] = 2 * cj + P[t][b][1];
                }
                for (int a = 0; a < 3; a++) {
                    F[6 * f + a] = v0 + (long)q[a][1] * m + q[a][0];
                    const int b = (a + 1) % 3;
                    F[6 * f + 3 + a] = v0 + (long)((q[a][1] + q[b][1]) / 2) * m + (q[a][0] + q[b][0]) / 2;
                }
                f++;
            }
        }
    return v;
}

/* A mortar pair of 6-node facets (a scene of order 2): the segments of
 * the vertex triangles, the multipliers at the vertices.  A slave pressed
 * uniformly into a non-matching flat master (the slave inside it): every
 * vertex's weighted gap is the gap and its pressure eps g, the tributary
 * areas sum to the slave's area, and the slave's nodal forces are the
 * consistent loads of that uniform pressure on quadratic facets,
 * p int N_a dA: 0 at the vertices, p A_f / 3 at each facet's midpoints
 * (degree-3 rule on the segments: exact for the products of quadratic
 * and linear shape functions).  Node-to-surface still refuses them. */
static void test_scene_pair_p2(void **state)
{
    (void)state;
    enum { NM = 3, NS = 4, NVM = (2 * NM + 1) * (2 * NM + 1), NV = NVM + (2 * NS + 1) * (2 * NS + 1) };
    static double X[3 * NV], u[3 * NV], R[3 * NV];
    static long Fm[6 * 2 * NM * NM], Fs[6 * 2 * NS * NS];
    grid6(NM, 0.0, 0.0, 1.0, 1, 0, X, Fm);
    grid6(NS, 0.0, 0.35, 0.7, 0, NVM, X, Fs);
    ffc_pair_opts o;
    long bad, nt, linked;
    ffc_scene *s = mortar_scene(6, NV, X, 2 * NS * NS, Fs, 2 * NM * NM, Fm, 3, &o);
    memset(u, 0, sizeof u);
    for (long v = NVM; v < NV; v++) u[3 * v + 2] = -0.001;
    assert_int_equal(ffc_scene_search(s, u, &linked, &bad), FFC_OK);
    memset(R, 0, sizeof R);
    assert_int_equal(ffc_scene_assemble(s, u, FFC_TANGENT_NONE, R, 0, NULL, NULL, NULL, &nt, &bad), FFC_OK);
    /* the expected slave forces: -p A_f / 3 at each midpoint (R is the force on the body, pushed up: -R) */
    static double Rz[NV];
    memset(Rz, 0, sizeof Rz);
    const double p = 1e3 * 0.001, Af = 0.5 * (0.7 / NS) * (0.7 / NS);
    for (long f = 0; f < 2 * NS * NS; f++)
        for (int a = 3; a < 6; a++) Rz[Fs[6 * f + a]] -= p * Af / 3.0;
    for (long v = NVM; v < NV; v++) {
        assert_close(R[3 * v + 2], Rz[v], 1e-13);
        assert_close(R[3 * v], 0.0, 1e-13);
        assert_close(R[3 * v + 1], 0.0, 1e-13);
    }
    const long np = ffc_scene_npoints(s, 0, 0);
    assert_int_equal(np, (NS + 1) * (NS + 1)); /* the vertices only */
    double *P = malloc(np * FFC_POINT_COLS * sizeof *P);
    long n;
    assert_int_equal(ffc_scene_points(s, u, 0, 0, np, P, &n, &bad), FFC_OK);
    double area = 0;
    for (long r = 0; r < n; r++) {
        assert_close(P[r * FFC_POINT_COLS + 3], -0.001, 1e-15);
        assert_close(P[r * FFC_POINT_COLS + 4], 1.0, 1e-12);
        area += P[r * FFC_POINT_COLS + 6];
    }
    assert_close(area, 0.49, 1e-14);
    free(P);
    o.method = FFC_METHOD_NTS;
    assert_int_equal(ffc_scene_add_pair(s, 2 * NS * NS, Fs, 2 * NM * NM, Fm, &o, &bad), FFC_ERR_NODES);
    ffc_scene_free(s);
}

/* The scene's mortar pair re-clips its segments at every evaluation: its
 * assembled tangent against central differences of its residual
 * (ffc_scene_assemble, h = 1e-7) on a kinked master, a slave surface
 * inside the master (every facet fully covered) and one reaching over the
 * master's rim (partly covered facets: the blended dual basis moves with
 * the segments), frictionless and with Coulomb friction (mu = 0.3 from a
 * committed state: stick and slip nodes).  nn = 6: quadratic facets,
 * straight-sided (the midpoints' motion the mean of their ends') or
 * curved (every node moved at random); finite: finite deformation (the
 * links in the current configuration).  Returns the largest error
 * relative to the tangent's largest entry over the four cases. */
static double follow_check(int nn, int curved, int qdeg, int finite)
{
    enum { CAP = 4000000 };
    const int NM = nn == 3 ? 3 : 2, NS = nn == 3 ? 4 : 3; /* (6-node facets: as many nodes on fewer cells) */
    const long NVM = nn == 3 ? (NM + 1) * (NM + 1) : (2 * NM + 1) * (2 * NM + 1),
               NV = NVM + (nn == 3 ? (NS + 1) * (NS + 1) : (2 * NS + 1) * (2 * NS + 1)), nd = 3 * NV;
    double *X = malloc(nd * sizeof *X), *u = malloc(nd * sizeof *u), *up = malloc(nd * sizeof *up),
           *R = malloc(nd * sizeof *R), *Rp = malloc(nd * sizeof *Rp), *Rm = malloc(nd * sizeof *Rm),
           *K = malloc(nd * nd * sizeof *K);
    long *Fm = malloc(6 * 2 * NM * NM * sizeof *Fm), *Fs = malloc(6 * 2 * NS * NS * sizeof *Fs);
    long *Ti = malloc(CAP * sizeof *Ti), *Tj = malloc(CAP * sizeof *Tj);
    double *Tv = malloc(CAP * sizeof *Tv), worst = 0;
    for (int rim = 0; rim <= 1; rim++)
        for (int fric = 0; fric <= 1; fric++) {
            if (nn == 3) {
                grid(NM, 0.0, 0.0, 1.0, 1, 0, 0, X, Fm);
                grid(NS, 0.0, 0.35, rim ? 1.2 : 0.7, 0, 1, NVM, X, Fs);
            } else {
                grid6(NM, 0.0, 0.0, 1.0, 1, 0, X, Fm);
                grid6(NS, 0.0, 0.35, rim ? 1.2 : 0.7, 0, NVM, X, Fs);
            }
            uint64_t s = (nn == 3 ? 77 : 78) + rim;
            for (long v = 0; v < NV; v++) {
                u[3 * v] = test_rand(&s, -0.01, 0.01);
                u[3 * v + 1] = test_rand(&s, -0.01, 0.01);
                u[3 * v + 2] = v < NVM ? test_rand(&s, -0.01, 0.01) : test_rand(&s, -0.014, -0.01);
                for (int i = 0; i < 3; i++) up[3 * v + i] = u[3 * v + i] - test_rand(&s, -0.002, 0.002);
            }
            for (int side = 0; nn == 6 && !curved && side < 2; side++) { /* straight: midpoints follow their ends */
                const long *F = side ? Fs : Fm, nf = side ? 2 * NS * NS : 2 * NM * NM;
                for (long f = 0; f < nf; f++)
                    for (int a = 0; a < 3; a++)
                        for (int i = 0; i < 3; i++) {
                            const long m = F[6 * f + 3 + a], p0 = F[6 * f + a], p1 = F[6 * f + (a + 1) % 3];
                            u[3 * m + i] = 0.5 * (u[3 * p0 + i] + u[3 * p1 + i]);
                            up[3 * m + i] = 0.5 * (up[3 * p0 + i] + up[3 * p1 + i]);
                        }
            }
            ffc_effects fx = {fric, 0, finite};
            ffc_scene *sc;
            assert_int_equal(ffc_scene_create(nn, NV, X, 0, NULL, &fx, &sc), FFC_OK);
            ffc_pair_opts o = ffc_pair_defaults();
            o.method = FFC_METHOD_MORTAR;
            o.qdeg = qdeg;
            o.eps_n = 1e3;
            o.mu = fric ? 0.3 : 0.0;
            long bad, nt, linked;
            assert_int_equal(ffc_scene_add_pair(sc, 2 * NS * NS, Fs, 2 * NM * NM, Fm, &o, &bad), 0);
            assert_int_equal(ffc_scene_commit(sc, up), FFC_OK); /* the friction history */
            assert_int_equal(ffc_scene_search(sc, u, &linked, &bad), FFC_OK);
            memset(R, 0, nd * sizeof *R);
            assert_int_equal(ffc_scene_assemble(sc, u, FFC_TANGENT_CONSISTENT, R, CAP, Ti, Tj, Tv, &nt, &bad), FFC_OK);
            memset(K, 0, nd * nd * sizeof *K);
            for (long k = 0; k < nt; k++) K[Ti[k] * nd + Tj[k]] += Tv[k];
            double st = 0, sl = 0;
            ffc_scene_stat(sc, 0, "stick", 0, &st);
            ffc_scene_stat(sc, 0, "slip", 0, &sl);
            if (fric) assert_true(st > 0 && sl > 0);
            double err = 0, scale = 0;
            const double h = 1e-7;
            for (long l = 0; l < nd; l++) {
                const double u0 = u[l];
                memset(Rp, 0, nd * sizeof *Rp);
                memset(Rm, 0, nd * sizeof *Rm);
                u[l] = u0 + h;
                assert_int_equal(ffc_scene_assemble(sc, u, FFC_TANGENT_NONE, Rp, 0, NULL, NULL, NULL, &nt, &bad), FFC_OK);
                u[l] = u0 - h;
                assert_int_equal(ffc_scene_assemble(sc, u, FFC_TANGENT_NONE, Rm, 0, NULL, NULL, NULL, &nt, &bad), FFC_OK);
                u[l] = u0;
                for (long k = 0; k < nd; k++) {
                    err = fmax(err, fabs((Rp[k] - Rm[k]) / (2 * h) - K[k * nd + l]));
                    scale = fmax(scale, fabs(K[k * nd + l]));
                }
            }
            worst = fmax(worst, err / scale);
            ffc_scene_free(sc);
        }
    free(X); free(u); free(up); free(R); free(Rp); free(Rm); free(K);
    free(Fm); free(Fs); free(Ti); free(Tj); free(Tv);
    return worst;
}

/* linear facets: the tangent is the residual's exact derivative, relative
 * 1e-6 (measured 4e-10) */
static void test_scene_follow(void **state)
{
    (void)state;
    const double e = follow_check(3, 0, 2, 0);
    if (!(e <= 1e-6)) fail_msg("linear facets: tangent error %.3g of its scale", e);
}

/* 6-node facets (2 x 2 and 3 x 3 cells: as many nodes as the linear
 * case).  Straight-sided, the integrands are polynomials that the rules of
 * degree 3 (segment triangles; the degree-4 rule) and 5 (moving edges)
 * integrate exactly, and the tangent is the residual's exact derivative:
 * relative 1e-6, small strain and finite deformation (measured 5e-10).  Curved (each midpoint up to 0.02 off
 * its ends' mean, on facets of sizes 0.23 and 0.5), the tangent is the
 * derivative of the exact integrals, from which the rules' sums differ
 * by their error: it falls with the rules' degree (measured 1.4e-5 with
 * degree 3, 5.8e-8 with 6), asserted as below 1e-6 with degree 6 and
 * above 20 times that with degree 3. */
static void test_scene_follow_p2(void **state)
{
    (void)state;
    const double straight = fmax(follow_check(6, 0, 3, 0), follow_check(6, 0, 3, 1)), curved6 = follow_check(6, 1, 6, 0),
                 curved3 = follow_check(6, 1, 3, 0);
    if (!(straight <= 1e-6)) fail_msg("straight 6-node facets: tangent error %.3g of its scale", straight);
    if (!(curved6 <= 1e-6)) fail_msg("curved 6-node facets, degree 6: tangent error %.3g of its scale", curved6);
    if (!(curved3 > 20 * curved6))
        fail_msg("curved 6-node facets: error %.3g with degree 3 against %.3g with 6 (the rules' error?)", curved3, curved6);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_clip_random),
        cmocka_unit_test(test_clip_bad_input),
        cmocka_unit_test(test_segment_coverage),
        cmocka_unit_test(test_segment_motion),
        cmocka_unit_test(test_dual_basis),
        cmocka_unit_test(test_uniform_pressure),
        cmocka_unit_test(test_segment_tangent),
        cmocka_unit_test(test_resegmented_tangent),
        cmocka_unit_test(test_translation),
        cmocka_unit_test(test_search_bad_input),
        cmocka_unit_test(test_scene_pair),
        cmocka_unit_test(test_scene_follow),
        cmocka_unit_test(test_scene_pair_p2),
        cmocka_unit_test(test_scene_follow_p2),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
