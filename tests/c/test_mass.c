/* test_mass.c: the redistributed mass's interpolation (ffc_mass_spread)
 * against dense computations: row sums, idempotence, no mass on the spread
 * dofs, the total mass kept, kept rows, capacity and bad input; with the
 * dofs' positions, the rigid-body properties (mass, first and second
 * moments) of a tetrahedral block whose whole surface is spread, and the
 * rows counted inexact where the dofs off the surfaces lie on a plane. */
#include "ffc_test.h"

#define N 8

/* the consistent mass of a chain of N - 1 linear elements of mass 1 each,
 * as element triplets (duplicates on shared nodes) */
static long chain_mass(long Mi[], long Mj[], double Mv[])
{
    long t = 0;
    for (long e = 0; e + 1 < N; e++)
        for (int a = 0; a < 2; a++)
            for (int b = 0; b < 2; b++) {
                Mi[t] = e + a;
                Mj[t] = e + b;
                Mv[t++] = a == b ? 1.0 / 3.0 : 1.0 / 6.0;
            }
    return t;
}

static void dense(long nt, const long Ti[], const long Tj[], const double Tv[], double D[N][N])
{
    memset(D, 0, sizeof(double) * N * N);
    for (long t = 0; t < nt; t++) D[Ti[t]][Tj[t]] += Tv[t];
}

static void test_mass_chain(void **state)
{
    (void)state;
    long Mi[4 * N], Mj[4 * N], Ti[5 * N], Tj[5 * N], nt = 0, kept = -1, loose = -1;
    double Mv[4 * N], Tv[5 * N], spread[N] = {0}, M[N][N], T[N][N];
    const long nm = chain_mass(Mi, Mj, Mv);
    spread[0] = spread[N - 1] = 1;        /* the two ends: contact surfaces */
    spread[3] = 1;                        /* and one inner node */
    assert_int_equal(ffc_mass_spread(N, nm, Mi, Mj, Mv, NULL, NULL, spread, 5 * N, Ti, Tj, Tv, &nt, &kept, &loose), FFC_OK);
    assert_int_equal(kept, 0);
    dense(nm, Mi, Mj, Mv, M);
    dense(nt, Ti, Tj, Tv, T);
    /* an end takes its one neighbour; node 3 the mean of 2 and 4 */
    assert_close(T[0][1], 1.0, 1e-15);
    assert_close(T[N - 1][N - 2], 1.0, 1e-15);
    assert_close(T[3][2], 0.5, 1e-15);
    assert_close(T[3][4], 0.5, 1e-15);
    double mass0 = 0, mass1 = 0;
    for (int i = 0; i < N; i++) {
        double rs = 0;
        for (int j = 0; j < N; j++) {
            rs += T[i][j];
            double tt = 0;                /* T T = T */
            for (int k = 0; k < N; k++) tt += T[i][k] * T[k][j];
            assert_close(tt, T[i][j], 1e-15);
            mass0 += M[i][j];
        }
        assert_close(rs, 1.0, 1e-15);
    }
    /* M_red = T' M T: no mass on the spread dofs, the total mass kept */
    double R[N][N];
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) {
            R[i][j] = 0;
            for (int k = 0; k < N; k++)
                for (int l = 0; l < N; l++) R[i][j] += T[k][i] * M[k][l] * T[l][j];
            mass1 += R[i][j];
        }
    for (int j = 0; j < N; j++) {
        assert_close(R[0][j], 0.0, 1e-15);
        assert_close(R[3][j], 0.0, 1e-15);
        assert_close(R[j][N - 1], 0.0, 1e-15);
    }
    assert_close(mass1, mass0, 1e-14);
}

/* weights |M_ij| over a random symmetric matrix with negative entries
 * (as the consistent P2 mass has), against a dense computation */
static void test_mass_weights(void **state)
{
    (void)state;
    uint64_t s = 7;
    long Mi[N * N], Mj[N * N], Ti[N * N + N], Tj[N * N + N], nt = 0, kept = 0, loose = 0;
    double Mv[N * N], Tv[N * N + N], spread[N], T[N][N];
    long nm = 0;
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) {
            Mi[nm] = i;
            Mj[nm] = j;
            Mv[nm++] = i == j ? 1.0 : test_rand(&s, -0.2, 0.3);
        }
    for (int i = 0; i < N; i++) spread[i] = i % 3 == 0;
    assert_int_equal(ffc_mass_spread(N, nm, Mi, Mj, Mv, NULL, NULL, spread, N * N + N, Ti, Tj, Tv, &nt, &kept, &loose), FFC_OK);
    dense(nt, Ti, Tj, Tv, T);
    for (int i = 0; i < N; i++) {
        double sum = 0;
        for (int j = 0; j < N; j++)
            if (!spread[j]) sum += fabs(Mv[i * N + j]);
        for (int j = 0; j < N; j++) {
            double want = !spread[i] ? (i == j) : (spread[j] ? 0.0 : fabs(Mv[i * N + j]) / sum);
            assert_close(T[i][j], want, 1e-15);
        }
    }
}

/* a spread dof with no neighbour off the set keeps its row; the capacity
 * and bad input */
static void test_mass_kept_and_errors(void **state)
{
    (void)state;
    long Mi[4 * N], Mj[4 * N], Ti[5 * N], Tj[5 * N], nt = 0, kept = 0, loose = 0;
    double Mv[4 * N], Tv[5 * N], spread[N] = {0}, T[N][N];
    const long nm = chain_mass(Mi, Mj, Mv);
    spread[0] = spread[1] = spread[2] = 1;    /* nodes 0 and 1: every neighbour spread */
    assert_int_equal(ffc_mass_spread(N, nm, Mi, Mj, Mv, NULL, NULL, spread, 5 * N, Ti, Tj, Tv, &nt, &kept, &loose), FFC_OK);
    assert_int_equal(kept, 2);
    dense(nt, Ti, Tj, Tv, T);
    assert_close(T[0][0], 1.0, 0);
    assert_close(T[1][1], 1.0, 0);
    assert_close(T[0][1], 0.0, 0);
    assert_close(T[2][3], 1.0, 0);            /* node 2 takes node 3 */
    long need = nt;
    assert_int_equal(ffc_mass_spread(N, nm, Mi, Mj, Mv, NULL, NULL, spread, need - 1, Ti, Tj, Tv, &nt, &kept, &loose),
                     FFC_ERR_CAPACITY);
    assert_int_equal(nt, need);
    assert_int_equal(ffc_mass_spread(N, nm, Mi, Mj, Mv, NULL, NULL, NULL, 5 * N, Ti, Tj, Tv, &nt, &kept, &loose), FFC_ERR_NULL);
    assert_int_equal(ffc_mass_spread(0, nm, Mi, Mj, Mv, NULL, NULL, spread, 5 * N, Ti, Tj, Tv, &nt, &kept, &loose), FFC_ERR_SIZE);
    Mi[5] = N;
    assert_int_equal(ffc_mass_spread(N, nm, Mi, Mj, Mv, NULL, NULL, spread, 5 * N, Ti, Tj, Tv, &nt, &kept, &loose), FFC_ERR_INDEX);
    Mi[5] = 1;
    Mv[4] = NAN;
    assert_int_equal(ffc_mass_spread(N, nm, Mi, Mj, Mv, NULL, NULL, spread, 5 * N, Ti, Tj, Tv, &nt, &kept, &loose), FFC_ERR_NONFINITE);
    Mv[4] = 1.0 / 3.0;
    spread[6] = INFINITY;
    assert_int_equal(ffc_mass_spread(N, nm, Mi, Mj, Mv, NULL, NULL, spread, 5 * N, Ti, Tj, Tv, &nt, &kept, &loose), FFC_ERR_NONFINITE);
}

/* a block of nx x ny x nz unit cubes, 6 tetrahedra each (Kuhn: every
 * tetrahedron holds the cube's diagonal from its lowest corner), nodes at
 * the grid points perturbed by up to 0.1 (along z: jz times that); the scalar consistent P1 mass
 * (V / 20 (1 + delta_ab)) as element triplets, the boundary nodes spread */
enum { BX = 3, BY = 3, BZ = 3, BN = (BX + 1) * (BY + 1) * (BZ + 1), BM = 16 * 6 * BX * BY * BZ };
static long block_node(int i, int j, int k, int ny, int nz) { return ((long)i * (ny + 1) + j) * (nz + 1) + k; }
static long block_mass(int nx, int ny, int nz, double jz, double X[], long Mi[], long Mj[], double Mv[], double spread[])
{
    uint64_t s = 11;
    for (int i = 0; i <= nx; i++)
        for (int j = 0; j <= ny; j++)
            for (int k = 0; k <= nz; k++) {
                long a = block_node(i, j, k, ny, nz);
                X[3 * a] = i + test_rand(&s, -0.1, 0.1);
                X[3 * a + 1] = j + test_rand(&s, -0.1, 0.1);
                X[3 * a + 2] = k + jz * test_rand(&s, -0.1, 0.1);
                spread[a] = i == 0 || i == nx || j == 0 || j == ny || k == 0 || k == nz;
            }
    static const int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    long t = 0;
    for (int i = 0; i < nx; i++)
        for (int j = 0; j < ny; j++)
            for (int k = 0; k < nz; k++)
                for (int p = 0; p < 6; p++) {
                    int c[3] = {i, j, k};
                    long v[4];
                    v[0] = block_node(c[0], c[1], c[2], ny, nz);
                    for (int q = 0; q < 3; q++) {
                        c[perm[p][q]]++;
                        v[q + 1] = block_node(c[0], c[1], c[2], ny, nz);
                    }
                    double e[3][3];
                    for (int q = 0; q < 3; q++)
                        for (int r = 0; r < 3; r++) e[q][r] = X[3 * v[q + 1] + r] - X[3 * v[0] + r];
                    double vol = fabs(e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1])
                                      - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0])
                                      + e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) / 6;
                    for (int a = 0; a < 4; a++)
                        for (int b = 0; b < 4; b++) {
                            Mi[t] = v[a];
                            Mj[t] = v[b];
                            Mv[t++] = vol / 20 * (a == b ? 2 : 1);
                        }
                }
    return t;
}

/* f' M g for the dense M [n][n] */
static double bilinear(long n, const double *M, const double f[], const double g[])
{
    double s = 0;
    for (long i = 0; i < n; i++)
        for (long j = 0; j < n; j++) s += f[i] * M[i * n + j] * g[j];
    return s;
}

/* the whole surface spread (the hard case: corners with no neighbour off
 * the surface, taken from ring 2): T reproduces 1, x, y, z, T T = T, and
 * the moments of order 0, 1 and 2 of M_red = T' M T are M's (the mass,
 * the centre of mass and the inertia tensor of any rigid motion) */
static void test_mass_rigid(void **state)
{
    (void)state;
    static double X[3 * BN], Mv[BM], spread[BN], Tv[BN * BN], T[BN * BN], M[BN * BN], R[BN * BN], f[4][BN];
    static long Mi[BM], Mj[BM], Ti[BN * BN], Tj[BN * BN];
    long nt = 0, kept = -1, loose = -1;
    const long nm = block_mass(BX, BY, BZ, 1, X, Mi, Mj, Mv, spread);
    assert_int_equal(ffc_mass_spread(BN, nm, Mi, Mj, Mv, X, NULL, spread, BN * BN, Ti, Tj, Tv, &nt, &kept, &loose), FFC_OK);
    assert_int_equal(kept, 0);
    assert_int_equal(loose, 0);
    memset(T, 0, sizeof T);
    memset(M, 0, sizeof M);
    for (long t = 0; t < nt; t++) T[Ti[t] * BN + Tj[t]] += Tv[t];
    for (long t = 0; t < nm; t++) M[Mi[t] * BN + Mj[t]] += Mv[t];
    for (long a = 0; a < BN; a++) {
        f[0][a] = 1;
        for (int c = 0; c < 3; c++) f[c + 1][a] = X[3 * a + c];
    }
    for (int q = 0; q < 4; q++)              /* T f = f for the affine fields */
        for (long i = 0; i < BN; i++) {
            double s = 0;
            for (long j = 0; j < BN; j++) s += T[i * BN + j] * f[q][j];
            assert_close(s, f[q][i], 1e-12 * (1 + fabs(f[q][i])));
        }
    for (long i = 0; i < BN; i++)            /* T T = T */
        for (long j = 0; j < BN; j++) {
            double s = 0;
            for (long k = 0; k < BN; k++) s += T[i * BN + k] * T[k * BN + j];
            assert_close(s, T[i * BN + j], 1e-12);
        }
    for (long i = 0; i < BN; i++)            /* R = T' M T */
        for (long j = 0; j < BN; j++) {
            double s = 0;
            for (long k = 0; k < BN; k++)
                if (T[k * BN + i] != 0)
                    for (long l = 0; l < BN; l++) s += T[k * BN + i] * M[k * BN + l] * T[l * BN + j];
            R[i * BN + j] = s;
        }
    for (long i = 0; i < BN; i++)
        if (spread[i])
            for (long j = 0; j < BN; j++) assert_close(R[i * BN + j], 0.0, 1e-14);
    for (int p = 0; p < 4; p++)              /* mass, first moments, second moments */
        for (int q = 0; q < 4; q++) {
            double want = bilinear(BN, M, f[p], f[q]);
            assert_close(bilinear(BN, R, f[p], f[q]), want, 1e-11 * fabs(want));
        }
}

/* a block two cubes thick, flat along z: the dofs off the surface lie on
 * one plane, so
 * no row reproduces the normal coordinate; they are counted inexact and
 * keep the mean (rows summing to 1: the mass kept) */
static void test_mass_flat(void **state)
{
    (void)state;
    enum { FX = 3, FY = 3, FZ = 2, FN = (FX + 1) * (FY + 1) * (FZ + 1), FM = 16 * 6 * FX * FY * FZ };
    static double X[3 * FN], Mv[FM], spread[FN], Tv[FN * FN];
    static long Mi[FM], Mj[FM], Ti[FN * FN], Tj[FN * FN];
    long nt = 0, kept = -1, loose = -1, nspread = 0;
    const long nm = block_mass(FX, FY, FZ, 0, X, Mi, Mj, Mv, spread);
    for (long a = 0; a < FN; a++) nspread += spread[a] != 0;
    assert_int_equal(ffc_mass_spread(FN, nm, Mi, Mj, Mv, X, NULL, spread, FN * FN, Ti, Tj, Tv, &nt, &kept, &loose), FFC_OK);
    assert_int_equal(kept, 0);
    assert_int_equal(loose, nspread);
    double rs[FN] = {0};
    for (long t = 0; t < nt; t++) {
        rs[Ti[t]] += Tv[t];
        assert_true(Tv[t] > 0);              /* the mean: positive weights */
    }
    for (long a = 0; a < FN; a++) assert_close(rs[a], 1.0, 1e-14);
    X[7] = NAN;
    assert_int_equal(ffc_mass_spread(FN, nm, Mi, Mj, Mv, X, NULL, spread, FN * FN, Ti, Tj, Tv, &nt, &kept, &loose),
                     FFC_ERR_NONFINITE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mass_chain),
        cmocka_unit_test(test_mass_weights),
        cmocka_unit_test(test_mass_kept_and_errors),
        cmocka_unit_test(test_mass_rigid),
        cmocka_unit_test(test_mass_flat),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
