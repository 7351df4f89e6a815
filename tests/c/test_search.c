/* test_search.c: contact search against an independent brute force
 * (projection onto every master facet), on flat, curved and perturbed
 * non-matching surfaces; rigid-motion invariance; capture and footprint;
 * the tie rule independent of order, facets without area, extreme units. */
#include "ffc_test.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    int nn;
    long nv, nf;
    double *x;   /* [nv*3] */
    long *F;     /* [nf*nn] */
} surf_t;

static void surf_free(surf_t *s) { free(s->x); free(s->F); }

/* Triangulated rectangle [x0,x1] x [y0,y1], n x m cells, heights z(x, y),
 * in-plane jitter of interior nodes, 3- or 6-node facets (mid-edge nodes
 * placed on z(x, y) as well).  Normals point along +z when up > 0. */
typedef double (*zfun_t)(double, double);
static surf_t make_grid(int nn, int n, int m, double x0, double y0, double x1, double y1,
                        zfun_t z, double jitter, int up, uint64_t seed)
{
    surf_t s;
    const int k = nn == 3 ? 1 : 2; /* nodes per cell edge */
    const int NX = k * n + 1, NY = k * m + 1;
    s.nn = nn;
    s.nv = (long)NX * NY;
    s.nf = 2L * n * m;
    s.x = malloc(s.nv * 3 * sizeof *s.x);
    s.F = malloc(s.nf * nn * sizeof *s.F);
    for (int j = 0; j < NY; j++)
        for (int i = 0; i < NX; i++) {
            double u = (double)i / (NX - 1), v = (double)j / (NY - 1);
            /* jitter whole cells' corner nodes only, keep mid-nodes central */
            if (i % k == 0 && j % k == 0 && i > 0 && j > 0 && i < NX - 1 && j < NY - 1) {
                u += test_rand(&seed, -jitter, jitter) / n;
                v += test_rand(&seed, -jitter, jitter) / m;
            }
            double *p = s.x + 3 * ((long)j * NX + i);
            p[0] = x0 + u * (x1 - x0);
            p[1] = y0 + v * (y1 - y0);
            p[2] = z(p[0], p[1]);
        }
    if (nn == 6) /* mid-edge nodes halfway between their corners, on z */
        for (int j = 0; j < NY; j++)
            for (int i = 0; i < NX; i++) {
                if (i % 2 == 0 && j % 2 == 0) continue;
                int ia = i - i % 2, ib = i + i % 2, ja = j - j % 2, jb = j + j % 2;
                if (i % 2 && j % 2) { ia = i - 1; ib = i + 1; ja = j + 1; jb = j - 1; } /* diagonal */
                double *p = s.x + 3 * ((long)j * NX + i);
                const double *a = s.x + 3 * ((long)ja * NX + ia), *b = s.x + 3 * ((long)jb * NX + ib);
                p[0] = 0.5 * (a[0] + b[0]);
                p[1] = 0.5 * (a[1] + b[1]);
                p[2] = z(p[0], p[1]);
            }
    long f = 0;
#define ID(i, j) ((long)(j) * NX + (i))
    for (int j = 0; j < m; j++)
        for (int i = 0; i < n; i++) {
            int I = k * i, J = k * j;
            /* two triangles: (a b d), (b c d) with a=(I,J) b=(I+k,J) c=(I+k,J+k) d=(I,J+k) */
            long t[2][6];
            long a = ID(I, J), b = ID(I + k, J), c = ID(I + k, J + k), d = ID(I, J + k);
            t[0][0] = a; t[0][1] = b; t[0][2] = d;
            t[1][0] = b; t[1][1] = c; t[1][2] = d;
            if (nn == 6) {
                t[0][3] = ID(I + 1, J); t[0][4] = ID(I + 1, J + 1); t[0][5] = ID(I, J + 1);
                t[1][3] = ID(I + 2, J + 1); t[1][4] = ID(I + 1, J + 2); t[1][5] = ID(I + 1, J + 1);
            }
            for (int q = 0; q < 2; q++, f++) {
                if (!up) { /* reverse orientation */
                    long tmp = t[q][1]; t[q][1] = t[q][2]; t[q][2] = tmp;
                    if (nn == 6) { tmp = t[q][3]; t[q][3] = t[q][5]; t[q][5] = tmp; }
                }
                for (int a2 = 0; a2 < nn; a2++) s.F[f * nn + a2] = t[q][a2];
            }
        }
#undef ID
    return s;
}

static double z_flat(double x, double y) { (void)x; (void)y; return 0.0; }
static double z_slave(double x, double y) { return 0.01 + 0.005 * sin(7 * x) * cos(5 * y); }
static double z_wavy(double x, double y) { return 0.03 * sin(6 * x + 1) * sin(4 * y); }
/* sphere of radius 0.6 centred at (0.5, 0.5, 0.62), lower cap */
static double z_ball(double x, double y)
{
    double r2 = (x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5);
    return 0.62 - sqrt(fmax(0.36 - r2, 0.0));
}

/* slave points of a link list */
static void slave_point(const surf_t *s, const ffc_link *lk, double p[3])
{
    double N[6];
    ffc_shape(s->nn, lk->xs, N, NULL);
    p[0] = p[1] = p[2] = 0;
    for (int a = 0; a < s->nn; a++)
        for (int i = 0; i < 3; i++) p[i] += N[a] * s->x[3 * s->F[lk->sf * s->nn + a] + i];
}

/* independent brute force: the closest master facet by direct projection */
static double brute(const surf_t *m, const double p[3], long *bf, ffc_proj *bpr)
{
    double best = INFINITY;
    *bf = -1;
    for (long f = 0; f < m->nf; f++) {
        double X[6][3];
        for (int a = 0; a < m->nn; a++)
            for (int i = 0; i < 3; i++) X[a][i] = m->x[3 * m->F[f * m->nn + a] + i];
        ffc_proj pr;
        if (ffc_project(m->nn, (const double(*)[3])X, p, &pr) < 0) continue;
        if (pr.dist < best) { best = pr.dist; *bf = f; *bpr = pr; }
    }
    return best;
}

/* Runs the search and checks every link against the brute force: same
 * distance to 1e-12 relative; same partner and gap unless the distances
 * tie (foot on an edge or vertex shared by both candidates); points
 * without link have no interior foot within the capture distance.
 * Returns the number of links with a partner. */
static long check_scene(const surf_t *m, const surf_t *s, int qdeg, const ffc_search_opts *o)
{
    ffc_tree *t;
    assert_int_equal(ffc_tree_build(m->nn, m->nf, m->F, m->nv, m->x, &t), FFC_OK);
    const int nq = ffc_quad_size(qdeg);
    const long nl = s->nf * nq;
    ffc_link *L = malloc(nl * sizeof *L), *B = malloc(nl * sizeof *B);
    int found = ffc_search(t, s->nn, s->nf, s->F, s->nv, s->x, qdeg, o, nl, L);
    assert_true(found >= 0);
    /* the library's own unpruned loop gives identical links */
    assert_int_equal(ffc_search_brute(t, s->nn, s->nf, s->F, s->nv, s->x, qdeg, o, nl, B), found);
    long ties = 0;
    for (long k = 0; k < nl; k++) {
        assert_int_equal(L[k].mf, B[k].mf);
        assert_int_equal(L[k].sf, k / nq);
        assert_int_equal(L[k].q, k % nq);
        double p[3];
        slave_point(s, &L[k], p);
        long bf;
        ffc_proj bpr;
        memset(&bpr, 0, sizeof bpr);
        double bd = brute(m, p, &bf, &bpr);
        if (L[k].mf < 0) {
            /* no link: the closest foot is clamped on the rim or beyond capture */
            if (bf >= 0 && bpr.where == FFC_FOOT_INSIDE) {
                double X[3][3];
                for (int a = 0; a < 3; a++)
                    for (int i = 0; i < 3; i++) X[a][i] = m->x[3 * m->F[bf * m->nn + a] + i];
                double h = sqrt(fmax(fmax((X[1][0]-X[0][0])*(X[1][0]-X[0][0])+(X[1][1]-X[0][1])*(X[1][1]-X[0][1])+(X[1][2]-X[0][2])*(X[1][2]-X[0][2]),
                                          (X[2][0]-X[1][0])*(X[2][0]-X[1][0])+(X[2][1]-X[1][1])*(X[2][1]-X[1][1])+(X[2][2]-X[1][2])*(X[2][2]-X[1][2])),
                                          (X[0][0]-X[2][0])*(X[0][0]-X[2][0])+(X[0][1]-X[2][1])*(X[0][1]-X[2][1])+(X[0][2]-X[2][2])*(X[0][2]-X[2][2])));
                if (!(bd > fmax(o->capture_abs, o->capture_rel * h) * (1 - 1e-12)))
                    fail_msg("point %ld: no link but interior foot at distance %g", k, bd);
            }
            continue;
        }
        /* the link's own distance */
        double X[6][3];
        for (int a = 0; a < m->nn; a++)
            for (int i = 0; i < 3; i++) X[a][i] = m->x[3 * m->F[L[k].mf * m->nn + a] + i];
        ffc_proj pr;
        assert_true(ffc_project(m->nn, (const double(*)[3])X, p, &pr) >= 0);
        assert_close(pr.dist, bd, 1e-12 * bd + 1e-15);
        if (L[k].mf == bf) {
            assert_close(L[k].gap, bpr.gap, 1e-12 * fabs(bpr.gap) + 1e-15);
        } else {
            /* a tie at a shared edge or vertex */
            assert_true(pr.where != FFC_FOOT_INSIDE || bpr.where != FFC_FOOT_INSIDE);
            ties++;
        }
    }
    (void)ties;
    free(L);
    free(B);
    ffc_tree_free(t);
    return found;
}

static void test_flat_nonmatching(void **state)
{
    (void)state;
    surf_t m = make_grid(3, 13, 11, 0, 0, 1, 1, z_flat, 0.3, 1, 1);
    surf_t s = make_grid(3, 9, 10, 0.05, 0.05, 0.95, 0.95, z_slave, 0.3, 0, 2);
    ffc_search_opts o = ffc_search_defaults();
    for (int q = 1; q <= 6; q++) {
        long found = check_scene(&m, &s, q, &o);
        assert_int_equal(found, s.nf * ffc_quad_size(q)); /* all inside the footprint */
    }
    surf_free(&m);
    surf_free(&s);
}

static void test_curved(void **state)
{
    (void)state;
    ffc_search_opts o = ffc_search_defaults();
    /* sphere (slave) over a plane (master), and the plane against a curved
     * 6-node sphere master */
    surf_t plane = make_grid(3, 16, 16, -0.1, -0.1, 1.1, 1.1, z_flat, 0.25, 1, 3);
    surf_t ball = make_grid(3, 12, 12, 0.2, 0.2, 0.8, 0.8, z_ball, 0.2, 0, 4);
    assert_true(check_scene(&plane, &ball, 4, &o) == ball.nf * 6);
    surf_t ball6 = make_grid(6, 8, 8, 0.1, 0.1, 0.9, 0.9, z_ball, 0.2, 0, 5);
    surf_t low = make_grid(3, 10, 10, 0.2, 0.2, 0.8, 0.8, z_flat, 0.25, 1, 6);
    for (long i = 0; i < low.nv; i++) low.x[3 * i + 2] = -0.05;
    check_scene(&ball6, &low, 3, &o);
    surf_t plane6 = make_grid(6, 9, 7, -0.1, -0.1, 1.1, 1.1, z_wavy, 0.2, 1, 8);
    assert_true(check_scene(&plane6, &ball, 2, &o) == ball.nf * 3);
    surf_free(&plane); surf_free(&ball); surf_free(&ball6); surf_free(&low); surf_free(&plane6);
}

static void test_perturbed(void **state)
{
    (void)state;
    ffc_search_opts o = ffc_search_defaults();
    for (int trial = 0; trial < 4; trial++) {
        surf_t m = make_grid(3, 20, 17, 0, 0, 1, 1, z_wavy, 0.35, 1, 10 + trial);
        surf_t s = make_grid(3, 11, 13, 0.02, 0.02, 0.98, 0.98, z_wavy, 0.35, 0, 20 + trial);
        uint64_t seed = 30 + trial;
        for (long i = 0; i < s.nv; i++) s.x[3 * i + 2] += test_rand(&seed, -0.02, 0.02);
        check_scene(&m, &s, 3, &o);
        surf_free(&m);
        surf_free(&s);
    }
}

/* rigid rotation and translation of the whole scene: same links */
static void test_rigid_motion(void **state)
{
    (void)state;
    surf_t m = make_grid(3, 12, 12, 0, 0, 1, 1, z_wavy, 0.3, 1, 40);
    surf_t s = make_grid(3, 9, 9, 0.05, 0.05, 0.95, 0.95, z_slave, 0.3, 0, 41);
    ffc_search_opts o = ffc_search_defaults();
    const int nq = 6;
    const long nl = s.nf * nq;
    ffc_link *A = malloc(nl * sizeof *A), *Bm = malloc(nl * sizeof *Bm);
    ffc_tree *t;
    assert_int_equal(ffc_tree_build(3, m.nf, m.F, m.nv, m.x, &t), FFC_OK);
    int fa = ffc_search(t, 3, s.nf, s.F, s.nv, s.x, 4, &o, nl, A);
    ffc_tree_free(t);
    double R[3][3];
    const double ax[3] = {1, 2, -0.5}, tr[3] = {3, -7, 11};
    test_rotation(ax, 2.1, R);
    for (long i = 0; i < m.nv; i++) { double y[3]; test_move(R, tr, m.x + 3 * i, y); memcpy(m.x + 3 * i, y, sizeof y); }
    for (long i = 0; i < s.nv; i++) { double y[3]; test_move(R, tr, s.x + 3 * i, y); memcpy(s.x + 3 * i, y, sizeof y); }
    assert_int_equal(ffc_tree_build(3, m.nf, m.F, m.nv, m.x, &t), FFC_OK);
    int fb = ffc_search(t, 3, s.nf, s.F, s.nv, s.x, 4, &o, nl, Bm);
    ffc_tree_free(t);
    assert_int_equal(fa, fb);
    for (long k = 0; k < nl; k++) {
        assert_int_equal(A[k].mf, Bm[k].mf);
        if (A[k].mf < 0) continue;
        assert_close(A[k].xm[0], Bm[k].xm[0], 1e-10);
        assert_close(A[k].xm[1], Bm[k].xm[1], 1e-10);
        assert_close(A[k].gap, Bm[k].gap, 1e-12 * 20);
        double Rn[3];
        const double zero[3] = {0, 0, 0};
        test_move(R, zero, A[k].n, Rn);
        for (int i = 0; i < 3; i++) assert_close(Rn[i], Bm[k].n[i], 1e-10);
    }
    free(A); free(Bm); surf_free(&m); surf_free(&s);
}

/* capture distance and footprint */
static void test_capture_footprint(void **state)
{
    (void)state;
    surf_t m = make_grid(3, 10, 10, 0, 0, 1, 1, z_flat, 0.0, 1, 50); /* h = 0.1 * sqrt 2 */
    /* slave: a row of tiny facets, heights 0.05 .. 0.5, and some outside */
    surf_t s = make_grid(3, 10, 1, -0.45, 0.3, 1.45, 0.31, z_flat, 0.0, 0, 51);
    for (long i = 0; i < s.nv; i++) s.x[3 * i + 2] = 0.02 + 0.5 * (s.x[3 * i] + 0.45) / 1.9;
    ffc_search_opts o = ffc_search_defaults();
    o.capture_rel = 0.0;
    o.capture_abs = 0.2;
    check_scene(&m, &s, 1, &o);
    ffc_tree *t;
    ffc_tree_build(3, m.nf, m.F, m.nv, m.x, &t);
    ffc_link L[20];
    int found = ffc_search(t, 3, s.nf, s.F, s.nv, s.x, 1, &o, 20, L);
    assert_true(found > 0 && found < 20);
    for (int k = 0; k < 20; k++) {
        double p[3];
        slave_point(&s, &L[k], p);
        /* (the row lies inside in y: past the rim by how far it is past x = 0 or 1) */
        const double over = fmax(0.0, fmax(-p[0], p[0] - 1.0));
        const int near = sqrt(over * over + p[2] * p[2]) <= 0.2;   /* (to the foot clamped on the rim) */
        assert_int_equal(L[k].mf >= 0, near && over <= p[2]);
        if (L[k].mf >= 0) assert_close(L[k].gap, p[2], 1e-14);
    }
    /* at the rim: a point past the rim by less than its distance from the
     * master plane (depth or height: the cone over the rim's edge) keeps
     * its link (clamped foot), by more it has none */
    const double pts[6][3] = {{1.001, 0.5, -0.01}, {1.02, 0.5, -0.01}, {1.001, 0.5, 0.01},
                              {-0.005, 0.5, -0.01}, {1.02, 0.5, 0.01}, {-0.005, 0.5, 0.01}};
    const int linked[6] = {1, 0, 1, 1, 0, 1};
    ffc_link Lp[6];
    assert_int_equal(ffc_search_points(t, 6, &pts[0][0], &o, Lp), 4);
    for (int k = 0; k < 6; k++) {
        assert_int_equal(Lp[k].sf, k);
        assert_int_equal(Lp[k].mf >= 0, linked[k]);
        if (linked[k]) assert_close(Lp[k].gap, pts[k][2], 1e-15);
    }
    /* bad options and sizes */
    o.capture_abs = -1;
    assert_int_equal(ffc_search(t, 3, s.nf, s.F, s.nv, s.x, 1, &o, 20, L), FFC_ERR_VALUE);
    o.capture_abs = NAN;
    assert_int_equal(ffc_search(t, 3, s.nf, s.F, s.nv, s.x, 1, &o, 20, L), FFC_ERR_VALUE);
    o = ffc_search_defaults();
    assert_int_equal(ffc_search(t, 3, s.nf, s.F, s.nv, s.x, 9, &o, 20, L), FFC_ERR_QUAD);
    assert_int_equal(ffc_search(t, 3, s.nf, s.F, s.nv, s.x, 2, &o, 20, L), FFC_ERR_CAPACITY);
    assert_int_equal(ffc_search(t, 3, 0, s.F, s.nv, s.x, 1, &o, 20, L), FFC_ERR_EMPTY);
    s.x[4] = INFINITY;
    assert_int_equal(ffc_search(t, 3, s.nf, s.F, s.nv, s.x, 1, &o, 20, L), FFC_ERR_NONFINITE);
    ffc_tree_free(t);
    ffc_tree *t2 = (ffc_tree *)1;
    assert_int_equal(ffc_tree_build(3, 0, m.F, m.nv, m.x, &t2), FFC_ERR_EMPTY);
    assert_null(t2);
    m.x[5] = NAN;
    assert_int_equal(ffc_tree_build(3, m.nf, m.F, m.nv, m.x, &t2), FFC_ERR_NONFINITE);
    surf_free(&m); surf_free(&s);
}

/* a refit after moving the master keeps queries exact */
static void test_refit(void **state)
{
    (void)state;
    surf_t m = make_grid(3, 15, 15, 0, 0, 1, 1, z_flat, 0.3, 1, 60);
    surf_t s = make_grid(3, 8, 8, 0.1, 0.1, 0.9, 0.9, z_slave, 0.3, 0, 61);
    ffc_tree *t;
    ffc_tree_build(3, m.nf, m.F, m.nv, m.x, &t);
    for (long i = 0; i < m.nv; i++) m.x[3 * i + 2] = z_wavy(m.x[3 * i], m.x[3 * i + 1]);
    assert_int_equal(ffc_tree_refit(t, m.x), FFC_OK);
    const long nl = s.nf * 3;
    ffc_link *A = malloc(nl * sizeof *A);
    ffc_search_opts o = ffc_search_defaults();
    assert_true(ffc_search(t, 3, s.nf, s.F, s.nv, s.x, 2, &o, nl, A) >= 0);
    ffc_tree_free(t);
    /* equal to a fresh build */
    long found = check_scene(&m, &s, 2, &o);
    long cnt = 0;
    for (long k = 0; k < nl; k++) cnt += A[k].mf >= 0;
    assert_int_equal(cnt, found);
    free(A); surf_free(&m); surf_free(&s);
}

/* Far from the origin (coordinates 1e6, facets 1e-3: float coordinates
 * would be 0.06 apart) and on both parities of the tree's depth: the
 * traversal's float boxes, taken relative to the tree's centre, and the
 * batches of points that share one traversal, give the unpruned loop's
 * links; query points beyond twice the tree's half-width (the exact boxes'
 * path) too. */
static void test_far_offset(void **state)
{
    (void)state;
    const double off[3] = {1e6, -1e6, 1e6};
    const int sizes[2] = {7, 9}; /* 49 and 81 leaves: depth 6 and 7 */
    for (int c = 0; c < 2; c++) {
        const int n = sizes[c];
        surf_t m = make_grid(3, n, n, 0, 0, 1e-3, 1e-3, z_flat, 0.3, 1, 70 + c);
        surf_t s = make_grid(3, n + 2, n + 1, 0, 0, 1e-3, 1e-3, z_flat, 0.3, 0, 80 + c);
        uint64_t seed = 90 + c;
        for (long i = 0; i < m.nv; i++) {
            m.x[3 * i + 2] = 1e-4 * sin(5e3 * m.x[3 * i]) * cos(4e3 * m.x[3 * i + 1]);
            for (int k = 0; k < 3; k++) m.x[3 * i + k] += off[k];
        }
        for (long i = 0; i < s.nv; i++) {
            s.x[3 * i + 2] = test_rand(&seed, -1e-4, 1e-4);
            for (int k = 0; k < 3; k++) s.x[3 * i + k] += off[k];
        }
        ffc_search_opts o = ffc_search_defaults();
        ffc_tree *t;
        assert_int_equal(ffc_tree_build(3, m.nf, m.F, m.nv, m.x, &t), FFC_OK);
        /* the same links as the unpruned loop, bit for bit, and distances
         * within round-off of the independent brute force (the coordinates'
         * own round-off, 2.2e-10 here, ten times) */
        const long nl = s.nf * 3;
        ffc_link *A = malloc(nl * sizeof *A), *B = malloc(nl * sizeof *B);
        const int found = ffc_search(t, 3, s.nf, s.F, s.nv, s.x, 2, &o, nl, A);
        assert_true(found > nl / 2);
        assert_int_equal(ffc_search_brute(t, 3, s.nf, s.F, s.nv, s.x, 2, &o, nl, B), found);
        for (long k = 0; k < nl; k++) {
            assert_int_equal(A[k].mf, B[k].mf);
            if (A[k].mf < 0) continue;
            assert_true(A[k].gap == B[k].gap);
            double p[3];
            slave_point(&s, &A[k], p);
            long bf;
            ffc_proj bpr;
            double X[3][3];
            for (int a = 0; a < 3; a++)
                for (int i = 0; i < 3; i++) X[a][i] = m.x[3 * m.F[A[k].mf * 3 + a] + i];
            ffc_proj pr;
            assert_true(ffc_project(3, (const double(*)[3])X, p, &pr) >= 0);
            assert_close(pr.dist, brute(&m, p, &bf, &bpr), 10 * DBL_EPSILON * 1e6);
        }
        /* the same points through ffc_search_points (searched in
         * batches as well): the same partners and gaps */
        double *P = malloc(nl * 3 * sizeof *P);
        ffc_link *C = malloc(nl * sizeof *C);
        for (long k = 0; k < nl; k++) slave_point(&s, &A[k], P + 3 * k);
        assert_int_equal(ffc_search_points(t, nl, P, &o, C), found);
        for (long k = 0; k < nl; k++) {
            assert_int_equal(C[k].mf, A[k].mf);
            assert_true(C[k].gap == A[k].gap);
        }
        free(P);
        free(C);
        free(A);
        free(B);
        /* points beyond twice the tree's half-width */
        for (int k = 0; k < 4; k++) {
            const double P[3] = {off[0] + 5e-4 * k, off[1] - 1e-3 * k, off[2] + 2e-3 * (k + 1)};
            long f, bf;
            ffc_proj pr, bpr;
            assert_int_equal(ffc_tree_nearest(t, P, 1.0, &f, &pr), FFC_OK);
            assert_true(f >= 0);
            assert_close(pr.dist, brute(&m, P, &bf, &bpr), 10 * DBL_EPSILON * 1e6);
        }
        ffc_tree_free(t);
        surf_free(&m);
        surf_free(&s);
    }
}

/* the partner the documented rule gives, computed here from every facet's
 * projection: the facets within the tie tolerance of the closest one (in
 * squared distance: 2 d tol + tol^2, tol = 1e-12 d + 1e-13 hmax), of
 * them one with an interior foot, then the lowest index */
static long rule_partner(int nf, const double *x, const double p[3], double hmax)
{
    double d2[8];
    int in[8];
    double dmin = INFINITY;
    for (int f = 0; f < nf; f++) {
        ffc_proj pr;
        d2[f] = INFINITY;
        if (ffc_project(3, (const double(*)[3])(x + 9 * f), p, &pr) < 0) continue;
        d2[f] = pr.dist * pr.dist;
        in[f] = pr.where == FFC_FOOT_INSIDE;
        dmin = fmin(dmin, d2[f]);
    }
    const double d = sqrt(dmin), tol = 1e-12 * d + 1e-13 * hmax, lim = dmin + 2 * d * tol + tol * tol;
    long best = -1;
    for (int f = 0; f < nf; f++)
        if (d2[f] <= lim && (best < 0 || (in[f] && !in[best]))) best = f;
    return best;
}

/* Three facets whose pairwise ties form a cycle: A, the foot on an edge at
 * d^2 (1 + 1e-14); B, interior, d^2 + 0.55 T; C, interior, d^2 + 1.1 T (T the tie
 * tolerance). B ties A and wins (interior), C ties B, but A is closer than
 * C beyond T: a pairwise rule picks by the order it meets them. In every
 * order of the facets, the traversal, the warm-started batches and brute
 * force give the rule's answer (B). */
static void test_tie_order(void **state)
{
    (void)state;
    const double p[3] = {-1e-7, 0.0, 1.0}, hmax = sqrt(5.0); /* (A's foot clamped onto its edge) */
    const double tol = 1e-12 + 1e-13 * hmax, T = 2 * tol + tol * tol;
    const double zB = 1.0 - sqrt(1.0 + 0.55 * T), zC = 1.0 - sqrt(1.0 + 1.1 * T);
    const double geo[3][9] = {{0, -1, 0, 0, 1, 0, 2, 0, 0},                 /* A */
                              {-1, -1, zB, 1, -1, zB, 0, 1, zB},           /* B */
                              {-1, -1, zC, 1, -1, zC, 0, 1, zC}};          /* C */
    const int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int q = 0; q < 6; q++) {
        double x[27];
        long F[9];
        for (int f = 0; f < 3; f++) memcpy(x + 9 * f, geo[perm[q][f]], sizeof geo[0]);
        for (int k = 0; k < 9; k++) F[k] = k;
        const long want = rule_partner(3, x, p, hmax);
        assert_int_equal(perm[q][want], 1); /* B */
        ffc_tree *t;
        assert_int_equal(ffc_tree_build(3, 3, F, 9, x, &t), FFC_OK);
        long f;
        ffc_proj pr;
        assert_int_equal(ffc_tree_nearest(t, p, 10.0, &f, &pr), FFC_OK);
        assert_int_equal(f, want);
        /* a batch whose earlier points warm-start the last one from each facet */
        double P[12];
        for (int k = 0; k < 3; k++) {
            for (int i = 0; i < 3; i++) P[3 * k + i] = (x[9 * k + i] + x[9 * k + 3 + i] + x[9 * k + 6 + i]) / 3;
            P[3 * k + 2] += 0.1;
        }
        memcpy(P + 9, p, sizeof p);
        ffc_search_opts o = ffc_search_defaults();
        o.capture_rel = 10.0;
        ffc_link L[4];
        assert_true(ffc_search_points(t, 4, P, &o, L) >= 1);
        assert_int_equal(L[3].mf, want);
        /* the point as the centroid of a slave facet (degree 1): the
         * traversal and the library's unpruned loop */
        const double xs[9] = {p[0] - 1, p[1] - 1, p[2], p[0] + 1, p[1] - 1, p[2], p[0], p[1] + 2, p[2]};
        const long Fs[3] = {0, 1, 2};
        ffc_link S[1];
        assert_int_equal(ffc_quad_size(1), 1);
        assert_int_equal(ffc_search(t, 3, 1, Fs, 3, xs, 1, &o, 1, S), 1);
        assert_int_equal(S[0].mf, want);
        assert_int_equal(ffc_search_brute(t, 3, 1, Fs, 3, xs, 1, &o, 1, S), 1);
        assert_int_equal(S[0].mf, want);
        for (int k = 0; k < 3; k++) { /* one point at a time, warm started from facet k */
            assert_true(ffc_search_points(t, 1, P + 3 * k, &o, L) >= 0);
            ffc_link L2[2];
            double P2[6];
            memcpy(P2, P + 3 * k, 3 * sizeof *P2);
            memcpy(P2 + 3, p, sizeof p);
            assert_true(ffc_search_points(t, 2, P2, &o, L2) >= 1);
            assert_int_equal(L2[1].mf, want);
        }
        ffc_tree_free(t);
    }
}

/* A facet without area (two vertices at one point, or three on a line)
 * takes no point: ffc_project refuses it, and the search skips it in every
 * path, so that a point above the edge of a good facet links to it whether
 * the bad facet is met before or after (its distance, 0/0 for coincident
 * vertices, once won the tie rule) */
static void test_degenerate_facet(void **state)
{
    (void)state;
    const double bad[2][9] = {{5, 5, -5, 5, 5, -5, 5, 5, -4},       /* two vertices at one point */
                              {0, -0.5, 0, 0, 0, 0, 0, 0.5, 0}};    /* three on A's edge */
    for (int b = 0; b < 2; b++) {
        double x[18] = {0};
        memcpy(x, bad[b], sizeof bad[b]);
        const double A[9] = {0, -1, 0, 0, 1, 0, 2, 0, 0};
        memcpy(x + 9, A, sizeof A);
        long F[6] = {0, 1, 2, 3, 4, 5};
        ffc_tree *t;
        assert_int_equal(ffc_tree_build(3, 2, F, 6, x, &t), FFC_OK);
        /* points above A's edge x = 0 (the first warm-starts the second) */
        const double P[6] = {0, 0, 1, 0, 0.5, 1};
        ffc_search_opts o = ffc_search_defaults();
        o.capture_rel = 10.0;
        ffc_link L[2];
        assert_int_equal(ffc_search_points(t, 2, P, &o, L), 2);
        assert_int_equal(L[0].mf, 1);
        assert_int_equal(L[1].mf, 1);
        long f;
        ffc_proj pr;
        assert_int_equal(ffc_tree_nearest(t, P + 3, 10.0, &f, &pr), FFC_OK);
        assert_int_equal(f, 1);
        ffc_tree_free(t);
    }
}

/* Models in units far from 1 (1e20 and 1e-21: the traversal's float boxes
 * would overflow, or round up below float's smallest normal number, in
 * absolute units): the links are brute force's, bit for bit */
static void test_extreme_units(void **state)
{
    (void)state;
    const double scale[3] = {1e20, 1e-21, 1e-30};
    for (int c = 0; c < 3; c++) {
        const double L = scale[c];
        surf_t m = make_grid(3, 9, 9, 0, 0, L, L, z_flat, 0.3, 1, 110 + c);
        surf_t s = make_grid(3, 11, 10, 0, 0, L, L, z_flat, 0.3, 0, 120 + c);
        uint64_t seed = 130 + c;
        for (long i = 0; i < m.nv; i++) m.x[3 * i + 2] = 0.05 * L * sin(5.0 * m.x[3 * i] / L);
        for (long i = 0; i < s.nv; i++) s.x[3 * i + 2] = test_rand(&seed, -0.1, 0.1) * L;
        ffc_search_opts o = ffc_search_defaults();
        ffc_tree *t;
        assert_int_equal(ffc_tree_build(3, m.nf, m.F, m.nv, m.x, &t), FFC_OK);
        const long nl = s.nf * 3;
        ffc_link *A = malloc(nl * sizeof *A), *B = malloc(nl * sizeof *B), *C = malloc(nl * sizeof *C);
        double *P = malloc(nl * 3 * sizeof *P);
        const int found = ffc_search(t, 3, s.nf, s.F, s.nv, s.x, 2, &o, nl, A);
        assert_true(found > nl / 2);
        assert_int_equal(ffc_search_brute(t, 3, s.nf, s.F, s.nv, s.x, 2, &o, nl, B), found);
        for (long k = 0; k < nl; k++) slave_point(&s, &A[k], P + 3 * k);
        assert_int_equal(ffc_search_points(t, nl, P, &o, C), found);
        for (long k = 0; k < nl; k++) {
            assert_int_equal(A[k].mf, B[k].mf);
            assert_int_equal(C[k].mf, B[k].mf);
            if (A[k].mf >= 0) assert_true(A[k].gap == B[k].gap);
            long f;
            ffc_proj pr;
            assert_int_equal(ffc_tree_nearest(t, P + 3 * k, 10.0 * L, &f, &pr), FFC_OK);
            long bf;
            ffc_proj bpr;
            const double bd = brute(&m, P + 3 * k, &bf, &bpr);
            assert_true(f >= 0);
            assert_close(pr.dist, bd, 1e-12 * bd);
        }
        free(A); free(B); free(C); free(P);
        ffc_tree_free(t);
        surf_free(&m);
        surf_free(&s);
    }
}

/* Self-contact (o.self = 1): the slave facets are the master surface's
 * own.  A strip folded into a hairpin (two flat sheets a gap g apart,
 * joined by a half circle of radius g / 2, normals into the gap; the
 * lower sheet's facets numbered before the upper's in each row): points
 * on the lower sheet away from the fold link to the upper sheet, at gap g
 * with normal -z; no point links to its own facet, to one sharing a
 * vertex with it, to one whose normal does not oppose its facet's, or to
 * one of lower index (one pass: no two facets linked both ways); the
 * tree and the unpruned loop agree.  A quarter cylinder, merely curved:
 * no link at all with o.self = 1 (without it every point links to its own
 * facet at gap 0). */
static void map_hairpin(surf_t *s, double g)
{
    const double r = 0.5 * g, arc = 3.14159265358979323846 * r;
    for (long i = 0; i < s->nv; i++) {
        double *x = s->x + 3 * i, t = x[0];
        if (t <= 1.0) { x[0] = t; x[2] = 0.0; }
        else if (t < 1.0 + arc) { const double a = (t - 1.0) / r; x[0] = 1.0 + r * sin(a); x[2] = r - r * cos(a); }
        else { x[0] = 1.0 - (t - 1.0 - arc); x[2] = g; }
    }
}
/* a sheet folded at x = 1 into a V of opening angle a (the part x > 1
 * turned back over the rest): the facets next to the crease face each
 * other and share its vertices */
static void map_vfold(surf_t *s, double a)
{
    for (long i = 0; i < s->nv; i++) {
        double *x = s->x + 3 * i, t = x[0];
        if (t > 1.0) { x[0] = 1.0 - (t - 1.0) * cos(a); x[2] = (t - 1.0) * sin(a); }
    }
}
static void map_quarter(surf_t *s, double R)
{
    for (long i = 0; i < s->nv; i++) {
        double *x = s->x + 3 * i, a = x[0] / R;   /* arc length along x, then the cylinder about y */
        x[0] = R * sin(a);
        x[2] = R - R * cos(a);
    }
}
static void facet_normal(const surf_t *s, long f, double n[3])
{
    const double *a = s->x + 3 * s->F[f * s->nn], *b = s->x + 3 * s->F[f * s->nn + 1], *c = s->x + 3 * s->F[f * s->nn + 2];
    double e1[3], e2[3];
    for (int i = 0; i < 3; i++) { e1[i] = b[i] - a[i]; e2[i] = c[i] - a[i]; }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1]; n[1] = e1[2] * e2[0] - e1[0] * e2[2]; n[2] = e1[0] * e2[1] - e1[1] * e2[0];
}
/* a self partner: facets sf and mf share no corner and face each other */
static void check_self_partner(const surf_t *h, long sf, long mf)
{
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) assert_true(h->F[3 * sf + a] != h->F[3 * mf + b]);
    double ns[3], nm[3];
    facet_normal(h, sf, ns);
    facet_normal(h, mf, nm);
    assert_true(ns[0] * nm[0] + ns[1] * nm[1] + ns[2] * nm[2] < 0);
}
static void test_self(void **state)
{
    (void)state;
    const double g = 0.05, arc = 3.14159265358979323846 * 0.5 * g, len = 2.0 + arc;
    surf_t h = make_grid(3, 42, 6, 0.0, 0.0, len, 0.3, z_flat, 0.0, 1, 1);
    map_hairpin(&h, g);
    ffc_tree *t;
    assert_int_equal(ffc_tree_build(3, h.nf, h.F, h.nv, h.x, &t), FFC_OK);
    ffc_search_opts o = ffc_search_defaults();
    o.self = 1;
    const int qdeg = 2, nq = ffc_quad_size(qdeg);
    const long nl = h.nf * nq;
    ffc_link *L = malloc(nl * sizeof *L), *B = malloc(nl * sizeof *B);
    const int found = ffc_search(t, 3, h.nf, h.F, h.nv, h.x, qdeg, &o, nl, L);
    assert_int_equal(ffc_search_brute(t, 3, h.nf, h.F, h.nv, h.x, qdeg, &o, nl, B), found);
    long lower = 0;
    for (long k = 0; k < nl; k++) {
        assert_int_equal(L[k].mf, B[k].mf);
        double p[3];
        slave_point(&h, &L[k], p);
        if (p[2] == 0.0 && p[0] < 0.9) {   /* the lower sheet away from the fold */
            assert_true(L[k].mf >= 0);
            assert_close(L[k].gap, g, 1e-12);
            assert_close(L[k].n[2], -1.0, 1e-12);
            lower++;
        }
        if (L[k].mf >= 0) check_self_partner(&h, L[k].sf, L[k].mf);
    }
    assert_true(lower >= 20 * 6 * 2 * nq * 9 / 10);   /* (18 of the 20 cells along x, every point in them) */
    /* one pass: a link goes from the facet of lower index to the other,
     * never back */
    for (long k = 0; k < nl; k++) {
        if (L[k].mf < 0) continue;
        assert_true(L[k].mf > L[k].sf);
        for (long j = 0; j < nl; j++) assert_false(L[j].sf == L[k].mf && L[j].mf == L[k].sf);
    }
    free(L); free(B);
    /* the mortar pairing alike (ffc_mortar_pairs with o.self): every pair
     * from the facet of lower index, facing, sharing no corner; each facet
     * of the lower sheet away from the fold paired */
    long need = 0;
    assert_int_equal(ffc_mortar_pairs(t, h.nf, h.F, h.nv, h.x, &o, 0, NULL, &need), FFC_ERR_CAPACITY);
    long *mp = malloc(2 * (size_t)need * sizeof *mp);
    assert_int_equal(ffc_mortar_pairs(t, h.nf, h.F, h.nv, h.x, &o, need, mp, &need), (int)need);
    unsigned char *paired = calloc((size_t)h.nf, 1);
    for (long k = 0; k < need; k++) {
        const long sf = mp[2 * k], mf = mp[2 * k + 1];
        assert_true(mf > sf);
        check_self_partner(&h, sf, mf);
        paired[sf] = 1;
    }
    long lowerFacets = 0;
    for (long f = 0; f < h.nf; f++) {
        double c[3] = {0, 0, 0};
        for (int a = 0; a < 3; a++)
            for (int i = 0; i < 3; i++) c[i] += h.x[3 * h.F[3 * f + a] + i] / 3;
        if (c[2] == 0.0 && c[0] < 0.9) { assert_true(paired[f]); lowerFacets++; }
    }
    assert_true(lowerFacets >= 18 * 6 * 2);
    free(mp); free(paired);
    ffc_tree_free(t);
    /* a V fold of 30 degrees: the facets at the crease face each other
     * across it, but share its vertices: no link and no mortar pair
     * between two facets sharing a corner (the neighbour rule), while the
     * sheets away from the crease link */
    surf_t v = make_grid(3, 20, 4, 0.0, 0.0, 2.0, 0.2, z_flat, 0.0, 1, 3);
    map_vfold(&v, 30.0 * 3.14159265358979323846 / 180.0);
    assert_int_equal(ffc_tree_build(3, v.nf, v.F, v.nv, v.x, &t), FFC_OK);
    const long nvl = v.nf * nq;
    L = malloc(nvl * sizeof *L);
    const int vfound = ffc_search(t, 3, v.nf, v.F, v.nv, v.x, qdeg, &o, nvl, L);
    assert_true(vfound > 0);
    assert_int_equal(ffc_mortar_pairs(t, v.nf, v.F, v.nv, v.x, &o, 0, NULL, &need), FFC_ERR_CAPACITY);
    mp = malloc(2 * (size_t)need * sizeof *mp);
    assert_int_equal(ffc_mortar_pairs(t, v.nf, v.F, v.nv, v.x, &o, need, mp, &need), (int)need);
    for (long k = 0; k < nvl + need; k++) {
        const long sf = k < nvl ? L[k].sf : mp[2 * (k - nvl)], mf = k < nvl ? L[k].mf : mp[2 * (k - nvl) + 1];
        if (mf >= 0) check_self_partner(&v, sf, mf);
    }
    free(L); free(mp);
    ffc_tree_free(t);
    surf_free(&v);
    /* merely curved: no partner anywhere */
    surf_t c = make_grid(3, 16, 4, 0.0, 0.0, 0.5 * 3.14159265358979323846 * 0.2, 0.2, z_flat, 0.2, 1, 2);
    map_quarter(&c, 0.2);
    assert_int_equal(ffc_tree_build(3, c.nf, c.F, c.nv, c.x, &t), FFC_OK);
    const long ncl = c.nf * nq;
    L = malloc(ncl * sizeof *L);
    assert_int_equal(ffc_search(t, 3, c.nf, c.F, c.nv, c.x, qdeg, &o, ncl, L), 0);
    assert_int_equal(ffc_mortar_pairs(t, c.nf, c.F, c.nv, c.x, &o, 0, NULL, &need), 0);
    o.self = 0;
    assert_int_equal(ffc_search(t, 3, c.nf, c.F, c.nv, c.x, qdeg, &o, ncl, L), ncl);
    for (long k = 0; k < ncl; k++) assert_close(L[k].gap, 0.0, 1e-12);
    free(L);
    ffc_tree_free(t);
    surf_free(&h);
    surf_free(&c);
}

/* The pass-through check of a self pair (ffc_scene_self_passed): the
 * hairpin's upper sheet moved down through the lower one by more than the
 * capture distance in one step is caught (its points behind the lower
 * facets, on their open side at the commit); moved down within the gap,
 * or the whole hairpin moved far as one, nothing is. */
static void test_self_passed(void **state)
{
    (void)state;
    const double g = 0.05, arc = 3.14159265358979323846 * 0.5 * g, len = 2.0 + arc;
    surf_t h = make_grid(3, 42, 6, 0.0, 0.0, len, 0.3, z_flat, 0.0, 1, 1);
    map_hairpin(&h, g);
    ffc_effects fx = {0, 0, 0};
    ffc_scene *s;
    assert_int_equal(ffc_scene_create(3, h.nv, h.x, 0, NULL, &fx, &s), FFC_OK);
    ffc_pair_opts o = ffc_pair_defaults();
    o.search.self = 1;
    long bad, n;
    assert_int_equal(ffc_scene_add_pair(s, h.nf, h.F, h.nf, h.F, &o, &bad), 0);
    double *u = calloc(3 * (size_t)h.nv, sizeof *u);
    assert_int_equal(ffc_scene_commit(s, u), FFC_OK);
    assert_int_equal(ffc_scene_self_passed(s, u, &n, &bad), FFC_OK);
    assert_int_equal(n, 0);
    const double drop[3] = {0.02, 0.5, 0.0};   /* within the gap; through it, far; none (the rigid move below) */
    const long want[3] = {0, 1, 0};
    for (int c = 0; c < 3; c++) {
        for (long i = 0; i < h.nv; i++) {
            const int upper = h.x[3 * i + 2] > 0.99 * g && h.x[3 * i] < 0.9;
            for (int j = 0; j < 3; j++) u[3 * i + j] = c == 2 ? (j == 0 ? 1.0 : j == 2 ? -0.7 : 0.0) : 0.0;
            if (upper) u[3 * i + 2] -= drop[c];
        }
        assert_int_equal(ffc_scene_self_passed(s, u, &n, &bad), FFC_OK);
        if (want[c]) assert_true(n > 100);
        else assert_int_equal(n, 0);
    }
    free(u);
    ffc_scene_free(s);
    surf_free(&h);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_flat_nonmatching),
        cmocka_unit_test(test_curved),
        cmocka_unit_test(test_perturbed),
        cmocka_unit_test(test_rigid_motion),
        cmocka_unit_test(test_capture_footprint),
        cmocka_unit_test(test_refit),
        cmocka_unit_test(test_far_offset),
        cmocka_unit_test(test_tie_order),
        cmocka_unit_test(test_degenerate_facet),
        cmocka_unit_test(test_extreme_units),
        cmocka_unit_test(test_self),
        cmocka_unit_test(test_self_passed),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
