/* test_rigid.c: the rigid motions that prescribed dofs leave free, per body:
 * counts, the motions vanish on every prescribed dof, translations and
 * axes orthonormal, axis points, capacity and bad input. */
#include "ffc_test.h"

/* two bodies: tetrahedra 0-1 share the face (1, 2, 3): nodes 0-4; the
 * single tetrahedron 2 is apart: nodes 5-8, three of them at z = 1 */
#define NV 9
static const double X[3 * NV] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1,
                                 5, 0, 1, 6, 0, 1, 5, 1, 1, 5, 0, 2};
static const long T[12] = {0, 1, 2, 3, 1, 2, 3, 4, 5, 6, 7, 8};

/* the displacement of motion o at x */
static void motion_at(const ffc_motion *o, const double x[3], double u[3])
{
    const double r[3] = {x[0] - o->p[0], x[1] - o->p[1], x[2] - o->p[2]};
    u[0] = o->t[0] + o->w[1] * r[2] - o->w[2] * r[1];
    u[1] = o->t[1] + o->w[2] * r[0] - o->w[0] * r[2];
    u[2] = o->t[2] + o->w[0] * r[1] - o->w[1] * r[0];
}

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* each of the n motions (of body 1: nodes 5-8) is zero on every prescribed dof */
static void assert_held_dofs_still(const ffc_motion m[], long n, const double fixed[3 * NV])
{
    for (long i = 0; i < n; i++)
        for (int a = 5; a < NV; a++) {
            double u[3];
            motion_at(&m[i], X + 3 * a, u);
            for (int d = 0; d < 3; d++)
                if (fixed[3 * a + d] != 0) assert_close(u[d], 0.0, 1e-12);
        }
}

/* nothing prescribed: per body 3 translations then 3 turns about its
 * centroid, each set orthonormal, no slide */
static void test_all_free(void **state)
{
    (void)state;
    ffc_motion m[12];
    long n = 0;
    assert_int_equal(ffc_rigid_free(NV, X, 3, T, NULL, NULL, 12, m, &n), FFC_OK);
    assert_int_equal(n, 12);
    const double c[2][3] = {{0.4, 0.4, 0.4}, {5.25, 0.25, 1.25}};
    for (int b = 0; b < 2; b++) {
        const ffc_motion *o = m + 6 * b;
        for (int i = 0; i < 6; i++) {
            assert_int_equal(o[i].body, b ? 5 : 0);
            for (int d = 0; d < 3; d++) assert_close(o[i].x[d], X[3 * o[i].body + d], 0.0);
            const double *v = i < 3 ? o[i].t : o[i].w;
            assert_close(v[i % 3], 1.0, 1e-12);                 /* along x, y, z in turn */
            if (i >= 3) assert_close(dot(o[i].t, o[i].t), 0.0, 1e-24); /* no slide */
            assert_int_equal(o[i].tet, b ? 2 : 0);
            for (int j = i < 3 ? 0 : 3; j < i; j++) assert_close(dot(v, j < 3 ? o[j].t : o[j].w), 0.0, 1e-12);
            if (i >= 3)
                for (int d = 0; d < 3; d++) assert_close(o[i].p[d], c[b][d], 1e-12);
        }
    }
}

/* body 0 clamped, body 1 held in x and y at its three nodes of z = 1:
 * free are the translation along z and two turns about axes in the plane
 * z = 1; each vanishes on every prescribed dof */
static void test_held(void **state)
{
    (void)state;
    double fixed[3 * NV] = {0};
    for (int i = 0; i < 15; i++) fixed[i] = 1;
    for (int a = 5; a < 8; a++) fixed[3 * a] = fixed[3 * a + 1] = 1;
    ffc_motion m[6];
    long n = 0;
    assert_int_equal(ffc_rigid_free(NV, X, 3, T, fixed, NULL, 6, m, &n), FFC_OK);
    assert_int_equal(n, 3);
    assert_int_equal(m[0].body, 5);
    assert_close(fabs(m[0].t[2]), 1.0, 1e-12);
    for (int i = 1; i < 3; i++) {
        assert_close(m[i].w[2], 0.0, 1e-12);
        assert_close(m[i].p[2], 1.0, 1e-12);
        assert_close(dot(m[i].t, m[i].t), 0.0, 1e-24);
    }
    /* named along the coordinate axes they span: x, then y */
    assert_close(m[1].w[0], 1.0, 1e-12);
    assert_close(m[2].w[1], 1.0, 1e-12);
    assert_held_dofs_still(m, n, fixed);
    /* node 8 (z = 2) held in x as well: the turn about y (in the plane
     * z = 1) moves it in x and goes; the translation along z and the turn
     * about x stay */
    fixed[3 * 8] = 1;
    assert_int_equal(ffc_rigid_free(NV, X, 3, T, fixed, NULL, 6, m, &n), FFC_OK);
    assert_int_equal(n, 2);
    assert_held_dofs_still(m, n, fixed);
}

/* body 1 held in x at every node: the free translations are y and z
 * exactly (not a mix of them), with the turn about x through the centroid */
static void test_translations_named(void **state)
{
    (void)state;
    double fixed[3 * NV] = {0};
    for (int i = 0; i < 15; i++) fixed[i] = 1;
    for (int a = 5; a < NV; a++) fixed[3 * a] = 1;
    ffc_motion m[6];
    long n = 0;
    assert_int_equal(ffc_rigid_free(NV, X, 3, T, fixed, NULL, 6, m, &n), FFC_OK);
    assert_int_equal(n, 3);
    assert_close(m[0].t[1], 1.0, 1e-12);
    assert_close(m[1].t[2], 1.0, 1e-12);
    assert_close(m[2].w[0], 1.0, 1e-12);
}

/* two nodes on the z axis held in x and y: free are the translation along
 * z and the turn about the z axis itself (its point on the axis) */
static void test_axis(void **state)
{
    (void)state;
    const double Xa[12] = {0, 0, 0, 0, 0, 1, 1, 0, 0.5, 0, 1, 0.5};
    const long Ta[4] = {0, 1, 2, 3};
    double fixed[12] = {1, 1, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0};
    ffc_motion m[6];
    long n = 0;
    assert_int_equal(ffc_rigid_free(4, Xa, 1, Ta, fixed, NULL, 6, m, &n), FFC_OK);
    assert_int_equal(n, 2);
    assert_close(fabs(m[0].t[2]), 1.0, 1e-12);           /* the slide along z */
    assert_close(fabs(m[1].w[2]), 1.0, 1e-12);           /* the turn about z */
    assert_close(m[1].p[0], 0.0, 1e-12);                  /* through the z axis */
    assert_close(m[1].p[1], 0.0, 1e-12);
}

/* the amounts: body 1 held as in test_held, turned by 0.01 rad about x
 * (through (5, 0.25, 1), in line with its centroid) and moved 0.002 along
 * z: the turn about x reads 0.01, the one about y 0, the translation along
 * z the centroid's 0.002, to round-off */
static void test_amounts(void **state)
{
    (void)state;
    double fixed[3 * NV] = {0}, u[3 * NV] = {0};
    for (int i = 0; i < 15; i++) fixed[i] = 1;
    for (int a = 5; a < 8; a++) fixed[3 * a] = fixed[3 * a + 1] = 1;
    const double th = 0.01, tz = 0.002, p[3] = {5, 0.25, 1};
    for (int a = 5; a < NV; a++) {
        const double r[3] = {X[3 * a] - p[0], X[3 * a + 1] - p[1], X[3 * a + 2] - p[2]};
        u[3 * a + 1] = -th * r[2];
        u[3 * a + 2] = th * r[1] + tz;
    }
    ffc_motion m[6];
    long n = 0;
    assert_int_equal(ffc_rigid_free(NV, X, 3, T, fixed, u, 6, m, &n), FFC_OK);
    assert_int_equal(n, 3);
    assert_close(m[0].amount, tz, 1e-14);
    assert_close(m[1].amount, th, 1e-14);
    assert_close(m[2].amount, 0.0, 1e-14);
    /* without u: no amounts */
    assert_int_equal(ffc_rigid_free(NV, X, 3, T, fixed, NULL, 6, m, &n), FFC_OK);
    for (int i = 0; i < 3; i++) assert_close(m[i].amount, 0.0, 0.0);
}

static void test_capacity_and_bad_input(void **state)
{
    (void)state;
    ffc_motion m[2];
    long n = 0;
    assert_int_equal(ffc_rigid_free(NV, X, 3, T, NULL, NULL, 2, m, &n), FFC_ERR_CAPACITY);
    assert_int_equal(n, 12);
    assert_int_equal(ffc_rigid_free(NV, X, 3, T, NULL, NULL, 0, NULL, &n), FFC_ERR_CAPACITY);
    assert_int_equal(n, 12);
    const long bad[4] = {0, 1, 2, NV};
    assert_int_equal(ffc_rigid_free(NV, X, 1, bad, NULL, NULL, 2, m, &n), FFC_ERR_INDEX);
    assert_int_equal(ffc_rigid_free(NV, NULL, 1, T, NULL, NULL, 2, m, &n), FFC_ERR_NULL);
    assert_int_equal(ffc_rigid_free(NV, X, 0, T, NULL, NULL, 2, m, &n), FFC_ERR_SIZE);
    assert_int_equal(ffc_scene_free_motions(NULL, NULL, 2, m, &n), FFC_ERR_NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_all_free),
        cmocka_unit_test(test_held),
        cmocka_unit_test(test_axis),
        cmocka_unit_test(test_translations_named),
        cmocka_unit_test(test_amounts),
        cmocka_unit_test(test_capacity_and_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
