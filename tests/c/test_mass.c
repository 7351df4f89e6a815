/* test_mass.c: the redistributed mass's interpolation (ffc_mass_spread)
 * against dense computations: row sums, idempotence, no mass on the spread
 * dofs, the total mass kept, kept rows, capacity and bad input. */
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
    long Mi[4 * N], Mj[4 * N], Ti[5 * N], Tj[5 * N], nt = 0, kept = -1;
    double Mv[4 * N], Tv[5 * N], w[N], spread[N] = {0}, M[N][N], T[N][N];
    const long nm = chain_mass(Mi, Mj, Mv);
    spread[0] = spread[N - 1] = 1;        /* the two ends: contact surfaces */
    spread[3] = 1;                        /* and one inner node */
    assert_int_equal(ffc_mass_spread(N, nm, Mi, Mj, Mv, spread, 5 * N, Ti, Tj, Tv, &nt, &kept, w), FFC_OK);
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
    long Mi[N * N], Mj[N * N], Ti[N * N + N], Tj[N * N + N], nt = 0, kept = 0;
    double Mv[N * N], Tv[N * N + N], w[N], spread[N], T[N][N];
    long nm = 0;
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) {
            Mi[nm] = i;
            Mj[nm] = j;
            Mv[nm++] = i == j ? 1.0 : test_rand(&s, -0.2, 0.3);
        }
    for (int i = 0; i < N; i++) spread[i] = i % 3 == 0;
    assert_int_equal(ffc_mass_spread(N, nm, Mi, Mj, Mv, spread, N * N + N, Ti, Tj, Tv, &nt, &kept, w), FFC_OK);
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
    long Mi[4 * N], Mj[4 * N], Ti[5 * N], Tj[5 * N], nt = 0, kept = 0;
    double Mv[4 * N], Tv[5 * N], w[N], spread[N] = {0}, T[N][N];
    const long nm = chain_mass(Mi, Mj, Mv);
    spread[0] = spread[1] = spread[2] = 1;    /* nodes 0 and 1: every neighbour spread */
    assert_int_equal(ffc_mass_spread(N, nm, Mi, Mj, Mv, spread, 5 * N, Ti, Tj, Tv, &nt, &kept, w), FFC_OK);
    assert_int_equal(kept, 2);
    dense(nt, Ti, Tj, Tv, T);
    assert_close(T[0][0], 1.0, 0);
    assert_close(T[1][1], 1.0, 0);
    assert_close(T[0][1], 0.0, 0);
    assert_close(T[2][3], 1.0, 0);            /* node 2 takes node 3 */
    long need = nt;
    assert_int_equal(ffc_mass_spread(N, nm, Mi, Mj, Mv, spread, need - 1, Ti, Tj, Tv, &nt, &kept, w),
                     FFC_ERR_CAPACITY);
    assert_int_equal(nt, need);
    assert_int_equal(ffc_mass_spread(N, nm, Mi, Mj, Mv, NULL, 5 * N, Ti, Tj, Tv, &nt, &kept, w), FFC_ERR_NULL);
    assert_int_equal(ffc_mass_spread(0, nm, Mi, Mj, Mv, spread, 5 * N, Ti, Tj, Tv, &nt, &kept, w), FFC_ERR_SIZE);
    Mi[5] = N;
    assert_int_equal(ffc_mass_spread(N, nm, Mi, Mj, Mv, spread, 5 * N, Ti, Tj, Tv, &nt, &kept, w), FFC_ERR_INDEX);
    Mi[5] = 1;
    Mv[4] = NAN;
    assert_int_equal(ffc_mass_spread(N, nm, Mi, Mj, Mv, spread, 5 * N, Ti, Tj, Tv, &nt, &kept, w), FFC_ERR_NONFINITE);
    Mv[4] = 1.0 / 3.0;
    spread[6] = INFINITY;
    assert_int_equal(ffc_mass_spread(N, nm, Mi, Mj, Mv, spread, 5 * N, Ti, Tj, Tv, &nt, &kept, w), FFC_ERR_NONFINITE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mass_chain),
        cmocka_unit_test(test_mass_weights),
        cmocka_unit_test(test_mass_kept_and_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
