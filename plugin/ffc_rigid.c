/* ffc_rigid.c: the rigid motions of each body (tetrahedra joined by shared
 * nodes) that a set of prescribed dofs leaves free. */
#include "ffc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void dsyev_(const char *jobz, const char *uplo, const int *n, double *a, const int *lda, double *w, double *work,
            const int *lwork, int *info);

/* eigenvalues w[n] (ascending) and orthonormal eigenvectors (columns of
 * A[n*n], column-major) of the symmetric A; 0 or LAPACK's info */
static int sym_eig(int n, double A[], double w[])
{
    double work[64];
    int lwork = 64, info = 0;
    dsyev_("V", "U", &n, A, &n, w, work, &lwork, &info);
    return info;
}

static long root(long *up, long a)
{
    while (up[a] != a) {
        up[a] = up[up[a]];
        a = up[a];
    }
    return a;
}

/* the rows of B_a (u_a = B_a y, y = (t, w)) at node position x: u = t + w x r,
 * r = (x - c) / L */
static void rigid_rows(const double x[3], const double c[3], double L, double B[3][6])
{
    const double r[3] = {(x[0] - c[0]) / L, (x[1] - c[1]) / L, (x[2] - c[2]) / L};
    const double R[3][6] = {{1, 0, 0, 0, r[2], -r[1]}, {0, 1, 0, -r[2], 0, r[0]}, {0, 0, 1, r[1], -r[0], 0}};
    memcpy(B, R, sizeof R);
}

/* Names the span of nb orthogonal vectors v[q] (squared lengths n2[q] > 0):
 * nb orthonormal axes[][3] in it, the coordinate axes' projections onto
 * the span taken greedily (the longest first, each orthogonal to those
 * taken), so that x, y or z is named so when the span holds it. */
static void name_axes(int nb, const double *const v[], const double n2[], double axes[][3])
{
    for (int j = 0; j < nb; j++) {
        double best[3] = {0, 0, 0}, bn = -1.0;
        for (int e = 0; e < 3; e++) {
            double p[3] = {0, 0, 0};
            for (int q = 0; q < nb; q++) {
                const double a = v[q][e] / n2[q];
                for (int d = 0; d < 3; d++) p[d] += a * v[q][d];
            }
            for (int i = 0; i < j; i++) {
                const double pi = p[0] * axes[i][0] + p[1] * axes[i][1] + p[2] * axes[i][2];
                for (int d = 0; d < 3; d++) p[d] -= pi * axes[i][d];
            }
            const double pn = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
            if (pn > bn + 1e-9) {
                bn = pn;
                for (int d = 0; d < 3; d++) best[d] = p[d] / pn;
            }
        }
        for (int d = 0; d < 3; d++) axes[j][d] = best[d];
    }
}

/* The bodies: up[a] = the lowest node of node a's body (union-find over
 * the tetrahedra T[nt*4]), first[r] = the first tetrahedron of the body
 * whose lowest node is r (-1: none) */
static void bodies(long nv, long nt, const long T[], long up[], long first[])
{
    for (long a = 0; a < nv; a++) up[a] = a;
    for (long e = 0; e < nt; e++)
        for (int k = 0; k < 4; k++) {
            long r0 = root(up, T[4 * e]), r1 = root(up, T[4 * e + k]);
            if (r0 != r1) up[r0 > r1 ? r0 : r1] = r0 < r1 ? r0 : r1; /* the lower index is the root */
        }
    for (long a = 0; a < nv; a++) up[a] = root(up, a);
    for (long a = 0; a < nv; a++) first[a] = -1;
    for (long e = nt - 1; e >= 0; e--) first[up[T[4 * e]]] = e;
}

/* body b's centroid, added into c (zero); returns its radius of gyration */
static double body_frame(long nv, const double X[], const long up[], long b, double c[3])
{
    double L2 = 0.0;
    long m = 0;
    for (long a = b; a < nv; a++)
        if (up[a] == b) {
            for (int d = 0; d < 3; d++) c[d] += X[3 * a + d];
            m++;
        }
    for (int d = 0; d < 3; d++) c[d] /= (double)m;
    for (long a = b; a < nv; a++)
        if (up[a] == b)
            for (int d = 0; d < 3; d++) L2 += (X[3 * a + d] - c[d]) * (X[3 * a + d] - c[d]);
    return sqrt(L2 / (double)m);
}

/* the body's rigid part of u: alpha = (t_c, w L) minimizing
 * sum_a |u_a - B_a alpha|^2, N alpha = sum_a B_a' u_a, added into alpha
 * (zero); FFC_OK or FFC_ERR_SINGULAR */
static int rigid_part(long nv, const double X[], const double u[], const long up[], long b, const double c[3],
                      double L, double alpha[6])
{
    double N[36] = {0}, rhs[6] = {0}, lam[6];
    for (long a = b; a < nv; a++) {
        if (up[a] != b) continue;
        double B[3][6];
        rigid_rows(X + 3 * a, c, L, B);
        for (int d = 0; d < 3; d++)
            for (int i = 0; i < 6; i++) {
                rhs[i] += B[d][i] * u[3 * a + d];
                for (int j = 0; j < 6; j++) N[6 * j + i] += B[d][i] * B[d][j];
            }
    }
    if (sym_eig(6, N, lam)) return FFC_ERR_SINGULAR;
    for (int q = 0; q < 6; q++) {
        if (!(lam[q] > 1e-12 * lam[5])) continue; /* (a body of collinear nodes) */
        double vr = 0.0;
        for (int i = 0; i < 6; i++) vr += N[6 * q + i] * rhs[i];
        for (int i = 0; i < 6; i++) alpha[i] += N[6 * q + i] * vr / lam[q];
    }
    return FFC_OK;
}

/* The motions of body b free of the prescribed dofs (the Formulation
 * above ffc_rigid_free): returns k, the dimension of G's null space (0:
 * none), with its basis y_q added into Y[6*k] (zero) and W's eigenvalues
 * wv[k] (ascending), or FFC_ERR_SINGULAR */
static int free_basis(long nv, const double X[], const double fixed[], const long up[], long b, const double c[3],
                      double L, double Y[36], double wv[6])
{
    double G[36] = {0};
    if (fixed)
        for (long a = b; a < nv; a++) {
            if (up[a] != b) continue;
            double B[3][6];
            rigid_rows(X + 3 * a, c, L, B);
            for (int d = 0; d < 3; d++) {
                if (fixed[3 * a + d] == 0) continue;
                for (int i = 0; i < 6; i++)
                    for (int j = 0; j < 6; j++) G[6 * j + i] += B[d][i] * B[d][j];
            }
        }
    double g[6], Z[36];
    if (sym_eig(6, G, g)) return FFC_ERR_SINGULAR;
    int k = 0; /* null: below round-off of G's largest eigenvalue (0 when nothing is prescribed) */
    while (k < 6 && g[k] <= 1e-12 * g[5]) k++;
    if (k == 0) return 0;
    memcpy(Z, G, sizeof Z); /* the null space: Z's first k columns */
    double W[36] = {0};
    for (int i = 0; i < k; i++)
        for (int j = 0; j < k; j++)
            for (int d = 3; d < 6; d++) W[k * j + i] += Z[6 * i + d] * Z[6 * j + d];
    if (sym_eig(k, W, wv)) return FFC_ERR_SINGULAR;
    /* the basis y_q = Z v_q (v_q: W's eigenvectors); the rotation parts
     * of those with lambda_q > 0 are orthogonal with |w_q|^2 = lambda_q */
    for (int q = 0; q < k; q++)
        for (int i = 0; i < k; i++)
            for (int d = 0; d < 6; d++) Y[6 * q + d] += W[k * q + i] * Z[6 * i + d];
    return k;
}

/* Body b's k free motions (free_basis: Y, wv) into out[found ..] (those
 * up to cap), translations first, with their amounts in u (alpha);
 * returns found + k */
static long put_motions(const double X[], long b, long tet, const double c[3], double L, const double alpha[6],
                        int k, const double Y[36], const double wv[6], long cap, ffc_motion out[], long found)
{
    int q0 = 0; /* translations: lambda_q ~ 0, first (wv ascending); their span named (name_axes) */
    while (q0 < k && wv[q0] <= 1e-12) q0++;
    double dirs[3][3], n2[6];
    const double *vq[6];
    for (int q = 0; q < q0; q++) {
        vq[q] = Y + 6 * q;
        n2[q] = vq[q][0] * vq[q][0] + vq[q][1] * vq[q][1] + vq[q][2] * vq[q][2];
    }
    name_axes(q0, vq, n2, dirs);
    for (int j = 0; j < q0; j++, found++) {
        if (found >= cap) continue;
        ffc_motion *o = &out[found];
        o->body = b;
        o->tet = tet;
        for (int d = 0; d < 3; d++) {
            o->x[d] = X[3 * b + d];
            o->t[d] = dirs[j][d];
            o->w[d] = 0.0;
            o->p[d] = c[d];
        }
        o->amount = alpha[0] * o->t[0] + alpha[1] * o->t[1] + alpha[2] * o->t[2];
    }
    /* turns: unit axes u in the span of the w_q (name_axes);
     * y(u) = sum_q (w_q . u / lambda_q) y_q */
    double axes[3][3];
    const int na = k - q0;
    for (int q = q0; q < k; q++) {
        vq[q - q0] = Y + 6 * q + 3;
        n2[q - q0] = wv[q];
    }
    name_axes(na, vq, n2, axes);
    for (int j = 0; j < na; j++, found++) {
        if (found >= cap) continue;
        double y[6] = {0};
        for (int q = q0; q < k; q++) {
            const double *yq = Y + 6 * q;
            const double a = (yq[3] * axes[j][0] + yq[4] * axes[j][1] + yq[5] * axes[j][2]) / wv[q];
            for (int d = 0; d < 6; d++) y[d] += a * yq[d];
        }
        /* a screw: the axis, the slide along it per radian, the axis point nearest c */
        ffc_motion *o = &out[found];
        o->body = b;
        o->tet = tet;
        const double w[3] = {y[3] / L, y[4] / L, y[5] / L}, w2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
        const double tw = (y[0] * w[0] + y[1] * w[1] + y[2] * w[2]) / w2;
        const double tp[3] = {y[0] - tw * w[0], y[1] - tw * w[1], y[2] - tw * w[2]};
        const double wxt[3] = {w[1] * tp[2] - w[2] * tp[1], w[2] * tp[0] - w[0] * tp[2], w[0] * tp[1] - w[1] * tp[0]};
        for (int d = 0; d < 3; d++) {
            o->x[d] = X[3 * b + d];
            o->w[d] = w[d] / sqrt(w2);
            o->t[d] = tw * w[d] / sqrt(w2);
            o->p[d] = c[d] + wxt[d] / w2;
        }
        o->amount = (alpha[3] * o->w[0] + alpha[4] * o->w[1] + alpha[5] * o->w[2]) / L;
    }
    return found;
}

/* Formulation: the rigid motions of a body of nodes x_a with centroid c and
 * radius of gyration L are u(x) = t + (w / L) x (x - c), y = (t, w) in R^6.
 * A prescribed dof (a, d) asks u_d(x_a) = 0, a row e_d' B_a y of a 3x6
 * B_a = [I, -[x_a - c]_x / L]; the motions free of all of them are the null
 * space of G = sum over prescribed (a, d) of B_a' e_d e_d' B_a (6x6): its
 * eigenvalues up to 1e-12 x the largest (round-off; all of them when
 * nothing is prescribed). Within it the rotation parts'
 * Gram W = Z_w' Z_w splits pure translations (its null space) from
 * rotations, whose axes are taken along the coordinate axes where their
 * span allows; a rotation w' = w / L with a translation t is a screw about
 * the axis through p = c + (w' x t_perp) / |w'|^2 with the slide t_par
 * along it (t = t_par + t_perp, t_par parallel to w'). */
int ffc_rigid_free(long nv, const double X[], long nt, const long T[], const double fixed[], const double u[],
                   long cap, ffc_motion out[], long *n)
{
    if (!X || !T || !n || (cap > 0 && !out)) return FFC_ERR_NULL;
    if (nv < 1 || nt < 1 || cap < 0) return FFC_ERR_SIZE;
    for (long i = 0; i < 4 * nt; i++)
        if (T[i] < 0 || T[i] >= nv) return FFC_ERR_INDEX;
    long *up = malloc((size_t)nv * sizeof *up);        /* union-find parents, then each node's body (root) */
    long *first = malloc((size_t)nv * sizeof *first);  /* a body's first tetrahedron, by root */
    int st = FFC_OK;
    if (!up || !first) {
        st = FFC_ERR_MEMORY;
        goto done;
    }
    bodies(nv, nt, T, up, first);
    long found = 0;
    for (long b = 0; b < nv; b++) {
        if (up[b] != b || first[b] < 0) continue; /* b: a body's lowest node (a node in no tetrahedron: none) */
        double c[3] = {0, 0, 0};
        const double L = body_frame(nv, X, up, b, c);
        if (!(L > 0)) continue; /* a body of one point */
        double alpha[6] = {0, 0, 0, 0, 0, 0};
        if (u && (st = rigid_part(nv, X, u, up, b, c, L, alpha))) goto done;
        double Y[36] = {0}, wv[6];
        const int k = free_basis(nv, X, fixed, up, b, c, L, Y, wv);
        if (k < 0) {
            st = k;
            goto done;
        }
        if (k == 0) continue;
        found = put_motions(X, b, first[b], c, L, alpha, k, Y, wv, cap, out, found);
    }
    *n = found;
    if (found > cap) st = FFC_ERR_CAPACITY;
done:
    free(up);
    free(first);
    return st;
}
