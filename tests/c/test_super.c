/* test_super.c: the supernodal Cholesky factorization by subtrees
 * (ffc_super.c) against CHOLMOD's own numeric factorization of the same
 * analysis, for one, two and three sets of subtrees. */
#include "ffc_test.h"

#include <suitesparse/cholmod.h>

#include "ffc_super.h"

/* Two bodies' worth of a 3D grid operator (nx^3 nodes each, 3 dofs a
 * node, coupled to the 6 neighbours with random positive weights, the
 * diagonal dominant: symmetric positive definite), lower triangle, in
 * the triplets' order of a scattered assembly. */
static cholmod_sparse *grid_matrix(int nx, int bodies, uint64_t seed, cholmod_common *cc)
{
    const int nn = nx * nx * nx, n = 3 * nn * bodies;
    cholmod_triplet *T = cholmod_allocate_triplet(n, n, (size_t)n * 16, -1, CHOLMOD_REAL, cc);
    int *ti = T->i, *tj = T->j;
    double *tv = T->x;
    long c = 0;
    double *diag = calloc((size_t)n, sizeof(double));
    for (int b = 0; b < bodies; b++)
        for (int z = 0; z < nx; z++)
            for (int y = 0; y < nx; y++)
                for (int x = 0; x < nx; x++) {
                    const int a = b * nn + (z * nx + y) * nx + x;
                    const int nb[3] = {x + 1 < nx ? a + 1 : -1, y + 1 < nx ? a + nx : -1, z + 1 < nx ? a + nx * nx : -1};
                    for (int k = 0; k < 3; k++) {
                        if (nb[k] < 0) continue;
                        for (int d = 0; d < 3; d++)
                            for (int e = 0; e < 3; e++) {
                                const double v = d == e ? -test_rand(&seed, 0.5, 1.5) : test_rand(&seed, -0.1, 0.1);
                                const int i = 3 * nb[k] + d, j = 3 * a + e;
                                ti[c] = i; tj[c] = j; tv[c] = v; c++;
                                diag[i] += fabs(v);
                                diag[j] += fabs(v);
                            }
                    }
                }
    for (int i = 0; i < n; i++) { ti[c] = tj[c] = i; tv[c] = diag[i] + 0.01; c++; }
    T->nnz = (size_t)c;
    free(diag);
    cholmod_sparse *A = cholmod_triplet_to_sparse(T, (size_t)c, cc);
    cholmod_free_triplet(&T, cc);
    return A;
}

/* CHOLMOD's supernodal factor of A, and a second one of the same analysis
 * (its values to come) */
static void two_factors(cholmod_sparse *A, cholmod_common *cc, cholmod_factor **ref, cholmod_factor **mine)
{
    cc->supernodal = CHOLMOD_SUPERNODAL;
    *ref = cholmod_analyze(A, cc);
    assert_non_null(*ref);
    *mine = cholmod_copy_factor(*ref, cc);
    assert_non_null(*mine);
    assert_true(cholmod_factorize(A, *ref, cc));
    assert_int_equal(cc->status, CHOLMOD_OK);
    assert_true(cholmod_change_factor(CHOLMOD_REAL, 1, 1, 1, 1, *mine, cc));
    assert_non_null((*mine)->x);
    assert_true((*ref)->is_super && (*mine)->is_super);
}

/* Every value of L within 1e-12 of the largest (the same products summed
 * in another order: the updates of a column number at most a few hundred
 * here, each rounded at 1e-16 relative), and x = A \ b by the factor with
 * a residual at round-off. */
static void check_factor(const cholmod_factor *ref, cholmod_factor *mine, cholmod_sparse *A, cholmod_common *cc)
{
    const double *x0 = ref->x, *x1 = mine->x;
    double big = 0.0, err = 0.0;
    for (size_t k = 0; k < ref->xsize; k++) {
        if (fabs(x0[k]) > big) big = fabs(x0[k]);
        if (fabs(x0[k] - x1[k]) > err) err = fabs(x0[k] - x1[k]);
    }
    assert_true(big > 0.0);
    assert_true(err <= 1e-12 * big);
    cholmod_dense *b = cholmod_ones(A->nrow, 1, CHOLMOD_REAL, cc);
    cholmod_dense *x = cholmod_solve(CHOLMOD_A, mine, b, cc);
    assert_non_null(x);
    cholmod_dense *r = cholmod_copy_dense(b, cc);
    double mone[2] = {-1.0, 0.0}, pone[2] = {1.0, 0.0};
    cholmod_sdmult(A, 0, mone, pone, x, r, cc);   /* r = b - A x */
    assert_true(cholmod_norm_dense(r, 0, cc) <= 1e-12 * cholmod_norm_dense(x, 0, cc) * cholmod_norm_sparse(A, 0, cc));
    cholmod_free_dense(&b, cc);
    cholmod_free_dense(&x, cc);
    cholmod_free_dense(&r, cc);
}

/* the sets' values (in any order: the last first), those above them,
 * checked against CHOLMOD's; everything freed */
static void factor_check_free(ffc__super *w, int parts, cholmod_factor *ref, cholmod_factor *mine, cholmod_sparse *A,
                              cholmod_common *cc)
{
    for (int p = parts - 1; p >= 0; p--)
        assert_int_equal(ffc__super_numeric(w, mine, mine->x, p), FFC_OK);
    assert_int_equal(ffc__super_numeric(w, mine, mine->x, -1), FFC_OK);
    check_factor(ref, mine, A, cc);
    ffc__super_free(w);
    cholmod_free_factor(&ref, cc);
    cholmod_free_factor(&mine, cc);
    cholmod_free_sparse(&A, cc);
    cholmod_finish(cc);
}

static void by_parts(int parts, int bodies)
{
    cholmod_common cc;
    cholmod_start(&cc);
    cc.print = 0;
    cholmod_sparse *A = grid_matrix(9, bodies, 17 + (uint64_t)parts, &cc);
    cholmod_factor *ref, *mine;
    two_factors(A, &cc, &ref, &mine);
    int st = 0;
    ffc__super *w = ffc__super_create(mine, A, parts, &st);
    assert_int_equal(st, FFC_OK);
    assert_non_null(w);
    double sum = 0.0;
    for (int p = -1; p < parts; p++) sum += ffc__super_share(w, p);
    assert_close(sum, 1.0, 1e-12);
    /* the estimate of the split (its largest set, then f times those
     * above, f = (1 + 1 / parts) / 2) below f (the whole with the parts'
     * threads); two like bodies on two sets: one each */
    const double f = (1.0 + 1.0 / parts) / 2.0;
    double mx = 0.0;
    for (int p = 0; p < parts; p++) mx = fmax(mx, ffc__super_share(w, p));
    if (parts > 1) assert_true(mx + f * ffc__super_share(w, -1) < f);
    if (parts == 2 && bodies == 2) {
        assert_close(ffc__super_share(w, 0), 0.5, 1e-12);
        assert_close(ffc__super_share(w, 1), 0.5, 1e-12);
    }
    factor_check_free(w, parts, ref, mine, A, &cc);
}

static void test_one_set(void **state) { (void)state; by_parts(1, 1); }
static void test_two_sets_two_bodies(void **state) { (void)state; by_parts(2, 2); }
static void test_two_sets_one_body(void **state) { (void)state; by_parts(2, 1); }
static void test_three_sets(void **state) { (void)state; by_parts(3, 2); }

/* a matrix that is not positive definite: a pivot refused, not a NaN */
static void test_not_positive_definite(void **state)
{
    (void)state;
    cholmod_common cc;
    cholmod_start(&cc);
    cc.print = 0;
    cholmod_sparse *A = grid_matrix(6, 1, 5, &cc);
    const int *Ap = A->p, *Ai = A->i;
    double *Ax = A->x;
    for (int p = Ap[40]; p < Ap[41]; p++)
        if (Ai[p] == 40) Ax[p] = -Ax[p];
    cc.supernodal = CHOLMOD_SUPERNODAL;
    cholmod_factor *L = cholmod_analyze(A, &cc);
    assert_true(cholmod_change_factor(CHOLMOD_REAL, 1, 1, 1, 1, L, &cc));
    int st = 0;
    ffc__super *w = ffc__super_create(L, A, 2, &st);
    assert_non_null(w);
    int r = FFC_OK;
    for (int p = 0; p < 2 && r == FFC_OK; p++) r = ffc__super_numeric(w, L, L->x, p);
    if (r == FFC_OK) r = ffc__super_numeric(w, L, L->x, -1);
    assert_int_equal(r, FFC_ERR_SINGULAR);
    /* bad arguments */
    assert_int_equal(ffc__super_numeric(w, L, L->x, 2), FFC_ERR_SIZE);
    assert_int_equal(ffc__super_numeric(w, L, L->x, -2), FFC_ERR_SIZE);
    assert_int_equal(ffc__super_numeric(NULL, L, L->x, 0), FFC_ERR_SIZE);
    assert_null(ffc__super_create(L, A, 0, &st));
    assert_int_equal(st, FFC_ERR_UNAVAILABLE);
    ffc__super_free(w);
    cholmod_free_factor(&L, &cc);
    cholmod_free_sparse(&A, &cc);
    cholmod_finish(&cc);
}

/* one dense block (a single supernode): no split gains over the whole
 * with the threads, so none is made for two sets; one set factorizes it */
static void test_no_gain(void **state)
{
    (void)state;
    cholmod_common cc;
    cholmod_start(&cc);
    cc.print = 0;
    const int n = 30;
    cholmod_triplet *T = cholmod_allocate_triplet(n, n, n * (n + 1) / 2, -1, CHOLMOD_REAL, &cc);
    int *ti = T->i, *tj = T->j;
    double *tv = T->x;
    for (int j = 0; j < n; j++)
        for (int i = j; i < n; i++) { ti[T->nnz] = i; tj[T->nnz] = j; tv[T->nnz] = i == j ? 2.0 * n : 1.0 / (1 + i + j); T->nnz++; }
    cholmod_sparse *A = cholmod_triplet_to_sparse(T, T->nnz, &cc);
    cholmod_free_triplet(&T, &cc);
    cholmod_factor *ref, *mine;
    two_factors(A, &cc, &ref, &mine);
    assert_int_equal((int)mine->nsuper, 1);
    int st = 0;
    assert_null(ffc__super_create(mine, A, 2, &st));
    assert_int_equal(st, FFC_ERR_UNAVAILABLE);
    ffc__super *w = ffc__super_create(mine, A, 1, &st);
    assert_non_null(w);
    factor_check_free(w, 1, ref, mine, A, &cc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_set),
        cmocka_unit_test(test_two_sets_two_bodies),
        cmocka_unit_test(test_two_sets_one_body),
        cmocka_unit_test(test_three_sets),
        cmocka_unit_test(test_not_positive_definite),
        cmocka_unit_test(test_no_gain),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
