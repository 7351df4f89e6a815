/* petsc_test.h: the system the iterative-path tests solve (one process
 * and several ranks): linear elasticity on a box of P1 tetrahedra, its
 * bottom held by tgv rows, pressed on top, with an unsymmetric
 * penalty-like coupling on the top nodes (as a contact tangent is). */
#ifndef PETSC_TEST_H
#define PETSC_TEST_H

#include "ffc_test.h"

#define PB_C 5                               /* cells a side */
#define PB_NV ((PB_C + 1) * (PB_C + 1) * (PB_C + 1))
#define PB_N (3 * PB_NV)
#define PB_NT (6 * PB_C * PB_C * PB_C)
#define PB_CAP (PB_NT * 144 + PB_N + 8 * PB_NV)
#define PB_TGV 1e30

typedef struct {
    double X[3 * PB_NV];
    long T[4 * PB_NT];
    long Ti[PB_CAP], Tj[PB_CAP];
    double Tv[PB_CAP];
    long nt;                 /* triplets */
    double b[PB_N];
} pb_system;

static inline long pb_node(int i, int j, int k) { return i + (PB_C + 1) * (j + (PB_C + 1) * k); }

/* the box [0, 1]^3 (each cube six tetrahedra around its diagonal), E 1,
 * nu 0.3; the bottom (z = 0) on tgv rows, imposed value 0 (and 0.01 in x
 * at one node: a Dirichlet value the scaling must keep); top nodes pulled
 * down by 0.01 each, and coupled to their neighbour in x by 0.3 of the
 * vertical stiffness one way only */
static inline void pb_make(pb_system *s)
{
    for (int k = 0; k <= PB_C; k++)
        for (int j = 0; j <= PB_C; j++)
            for (int i = 0; i <= PB_C; i++) {
                const long v = pb_node(i, j, k);
                s->X[3 * v] = (double)i / PB_C;
                s->X[3 * v + 1] = (double)j / PB_C;
                s->X[3 * v + 2] = (double)k / PB_C;
            }
    static const int cube[6][4][3] = {
        {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 1}}, {{0, 0, 0}, {1, 1, 0}, {0, 1, 0}, {1, 1, 1}},
        {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {1, 1, 1}}, {{0, 0, 0}, {0, 1, 1}, {0, 0, 1}, {1, 1, 1}},
        {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}}, {{0, 0, 0}, {1, 0, 1}, {1, 0, 0}, {1, 1, 1}}};
    long t = 0;
    for (int k = 0; k < PB_C; k++)
        for (int j = 0; j < PB_C; j++)
            for (int i = 0; i < PB_C; i++)
                for (int c = 0; c < 6; c++, t++)
                    for (int a = 0; a < 4; a++)
                        s->T[4 * t + a] = pb_node(i + cube[c][a][0], j + cube[c][a][1], k + cube[c][a][2]);
    static double lam[PB_NT], mu[PB_NT];
    for (long e = 0; e < PB_NT; e++) { lam[e] = 0.3 / (1.3 * 0.4); mu[e] = 1.0 / 2.6; }
    long nnz = 0, bad = -1;
    assert_int_equal(ffc_elastic_p1(PB_NV, s->X, PB_NT, s->T, lam, mu, PB_CAP, s->Ti, s->Tj, s->Tv, &nnz, &bad), FFC_OK);
    memset(s->b, 0, sizeof s->b);
    for (int j = 0; j <= PB_C; j++)
        for (int i = 0; i <= PB_C; i++) {
            const long v = pb_node(i, j, 0), w = pb_node(i, j, PB_C);
            for (int c = 0; c < 3; c++) {
                s->Ti[nnz] = s->Tj[nnz] = 3 * v + c;
                s->Tv[nnz++] = PB_TGV;
            }
            s->b[3 * w + 2] = -0.01;
            if (i < PB_C) {   /* the one-way coupling */
                s->Ti[nnz] = 3 * w + 2; s->Tj[nnz] = 3 * pb_node(i + 1, j, PB_C) + 2; s->Tv[nnz++] = -0.3;
                s->Ti[nnz] = 3 * w + 2; s->Tj[nnz] = 3 * w + 2; s->Tv[nnz++] = 0.3;
            }
        }
    s->b[3 * pb_node(2, 2, 0)] = PB_TGV * 0.01;
    s->nt = nnz;
}

/* the top face's dofs into dofs[], ascending (the top nodes are the
 * last ones); returns their count */
static inline long pb_top_dofs(long dofs[])
{
    long nb = 0;
    for (int j = 0; j <= PB_C; j++)
        for (int i = 0; i <= PB_C; i++)
            for (int c = 0; c < 3; c++) dofs[nb++] = 3 * pb_node(i, j, PB_C) + c;
    return nb;
}

/* |S (b - A x)| / |S b|, S dividing the tgv rows by their diagonal */
static inline double pb_residual(const pb_system *s, const double x[])
{
    static double r[PB_N], d[PB_N];
    memcpy(r, s->b, sizeof r);
    memset(d, 0, sizeof d);
    for (long k = 0; k < s->nt; k++) {
        r[s->Ti[k]] -= s->Tv[k] * x[s->Tj[k]];
        if (s->Ti[k] == s->Tj[k]) d[s->Ti[k]] += s->Tv[k];
    }
    double rn = 0, bn = 0;
    for (long i = 0; i < PB_N; i++) {
        const double f = d[i] >= 1e20 ? 1.0 / d[i] : 1.0;
        rn += f * r[i] * f * r[i];
        bn += f * s->b[i] * f * s->b[i];
    }
    return sqrt(rn / bn);
}

static inline double pb_diff(const double x[], const double y[])
{
    double d = 0, n = 0;
    for (long i = 0; i < PB_N; i++) { d += (x[i] - y[i]) * (x[i] - y[i]); n += y[i] * y[i]; }
    return sqrt(d / n);
}

#endif
