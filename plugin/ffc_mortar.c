/* ffc_mortar.c: segment-to-segment (mortar) integration: convex polygon
 * clipping, the segments of a slave facet against the master facets it
 * overlaps, and the dual (biorthogonal) multiplier basis of a facet. */
#include "ffc.h"
#include "ffc_internal.h"

#include <math.h>
#include <string.h>

/* twice the signed area of the polygon p[n] */
static double area2(int n, const double p[][2])
{
    double a = 0.0;
    for (int i = 0; i < n; i++) {
        const int j = (i + 1) % n;
        a += p[i][0] * p[j][1] - p[j][0] * p[i][1];
    }
    return a;
}

/* Formulation (Sutherland-Hodgman).  Each edge (b_j, b_j+1) of the convex
 * counter-clockwise clip polygon b is a half-plane
 *     s(x) = (b_j+1 - b_j) x (x - b_j) >= 0;
 * the subject polygon is cut by one half-plane after the other: a vertex
 * with s >= 0 is kept, and an edge whose ends have s of opposite signs
 * adds its crossing x = p + s(p) / (s(p) - s(q)) (q - p).  The result of
 * convex polygons is convex, with at most na + nb vertices. */
int ffc_clip_polygon(int na, const double a[][2], int nb, const double b[][2], int cap, double out[][2])
{
    if (!a || !b || !out) return FFC_ERR_NULL;
    if (na < 3 || nb < 3 || na > FFC_CLIPMAX || nb > FFC_CLIPMAX) return FFC_ERR_SIZE;
    if (cap < na + nb) return FFC_ERR_CAPACITY;
    for (int i = 0; i < na; i++)
        if (!isfinite(a[i][0]) || !isfinite(a[i][1])) return FFC_ERR_NONFINITE;
    for (int i = 0; i < nb; i++)
        if (!isfinite(b[i][0]) || !isfinite(b[i][1])) return FFC_ERR_NONFINITE;
    if (!(area2(na, a) > 0) || !(area2(nb, b) > 0)) return FFC_ERR_DEGENERATE;
    double P[2 * FFC_CLIPMAX][2], Q[2 * FFC_CLIPMAX][2];
    int n = na;
    memcpy(P, a, (size_t)na * sizeof *P);
    for (int j = 0; j < nb && n > 0; j++) {
        const double *b0 = b[j], *b1 = b[(j + 1) % nb];
        const double ex = b1[0] - b0[0], ey = b1[1] - b0[1];
        double s[2 * FFC_CLIPMAX];
        for (int i = 0; i < n; i++) s[i] = ex * (P[i][1] - b0[1]) - ey * (P[i][0] - b0[0]);
        int m = 0;
        for (int i = 0; i < n; i++) {
            const int k = (i + 1) % n;
            if (m + 2 > 2 * FFC_CLIPMAX) return FFC_ERR_SIZE; /* not convex input */
            if (s[i] >= 0) { Q[m][0] = P[i][0]; Q[m][1] = P[i][1]; m++; }
            if ((s[i] >= 0) != (s[k] >= 0) && s[i] != s[k]) {
                const double t = s[i] / (s[i] - s[k]);
                Q[m][0] = P[i][0] + t * (P[k][0] - P[i][0]);
                Q[m][1] = P[i][1] + t * (P[k][1] - P[i][1]);
                m++;
            }
        }
        /* drop repeated vertices (a vertex on the cut line appears twice) */
        n = 0;
        for (int i = 0; i < m; i++) {
            const double *v = Q[i], *w = P[n > 0 ? n - 1 : 0];
            if (n > 0 && fabs(v[0] - w[0]) <= 1e-15 * (fabs(v[0]) + 1) && fabs(v[1] - w[1]) <= 1e-15 * (fabs(v[1]) + 1))
                continue;
            P[n][0] = v[0];
            P[n][1] = v[1];
            n++;
        }
        if (n > 1 && fabs(P[0][0] - P[n - 1][0]) <= 1e-15 * (fabs(P[0][0]) + 1) &&
            fabs(P[0][1] - P[n - 1][1]) <= 1e-15 * (fabs(P[0][1]) + 1))
            n--;
        if (n > na + nb) return FFC_ERR_SIZE; /* not convex input */
    }
    if (n < 3 || !(area2(n, (const double(*)[2])P) > 0)) return 0;
    memcpy(out, P, (size_t)n * sizeof *P);
    return n;
}

/* Formulation (segments).  The slave facet's vertex triangle s_0 s_1 s_2
 * spans the plane x(xi) = s_0 + xi_1 t_1 + xi_2 t_2, t_a = s_a - s_0.  A
 * master vertex y lies over the point of local coordinates
 *     xi = m^-1 [t_1 . (y - s_0), t_2 . (y - s_0)],   m_ab = t_a . t_b,
 * its projection along the slave normal.  The master triangle, projected,
 * is clipped against the reference triangle; the polygon is cut into a
 * fan of triangles from its first vertex, and each gets the Gauss rule of
 * degree qdeg: a point xi = v_0 + r_1 (v_i - v_0) + r_2 (v_i+1 - v_0)
 * with weight w_g 2 A_i (A_i its area in xi), so that the weights of a
 * fully covered facet sum to 1/2, as the facet's own rule does. */
int ffc_mortar_segment(int qdeg, const double Xs[3][3], const double Xm[3][3], long cap, double xi[][2],
                       double w[], double *covered)
{
    if (!Xs || !Xm || !xi || !w || !covered) return FFC_ERR_NULL;
    double rq[16][2], wq[16];
    const int nq = ffc_quad(qdeg, 16, rq, wq);
    if (nq < 0) return nq;
    double t[2][3], mt[2][2];
    for (int i = 0; i < 3; i++) {
        t[0][i] = Xs[1][i] - Xs[0][i];
        t[1][i] = Xs[2][i] - Xs[0][i];
        for (int a = 0; a < 3; a++)
            if (!isfinite(Xs[a][i]) || !isfinite(Xm[a][i])) return FFC_ERR_NONFINITE;
    }
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) mt[a][b] = ffc__dot(t[a], t[b]);
    const double det = mt[0][0] * mt[1][1] - mt[0][1] * mt[1][0];
    if (!(det > FFC__DEGEN_REL * FFC__DEGEN_REL * (mt[0][0] + mt[1][1]) * (mt[0][0] + mt[1][1])))
        return FFC_ERR_DEGENERATE;
    double pm[3][2];
    for (int b = 0; b < 3; b++) {
        double d[3] = {Xm[b][0] - Xs[0][0], Xm[b][1] - Xs[0][1], Xm[b][2] - Xs[0][2]};
        const double r0 = ffc__dot(t[0], d), r1 = ffc__dot(t[1], d);
        pm[b][0] = (mt[1][1] * r0 - mt[0][1] * r1) / det;
        pm[b][1] = (mt[0][0] * r1 - mt[1][0] * r0) / det;
    }
    *covered = 0.0;
    const double a2 = area2(3, (const double(*)[2])pm);
    if (!(fabs(a2) > 1e-14)) return 0; /* the master facet stands edge-on over the slave plane */
    if (a2 < 0) { /* facing facets project clockwise */
        double tmp[2] = {pm[1][0], pm[1][1]};
        pm[1][0] = pm[2][0]; pm[1][1] = pm[2][1];
        pm[2][0] = tmp[0]; pm[2][1] = tmp[1];
    }
    static const double ref[3][2] = {{0, 0}, {1, 0}, {0, 1}};
    double poly[2 * FFC_CLIPMAX][2];
    const int np = ffc_clip_polygon(3, ref, 3, (const double(*)[2])pm, 2 * FFC_CLIPMAX, poly);
    if (np <= 0) return np;
    long n = 0;
    for (int i = 1; i + 1 < np; i++) {
        const double e1[2] = {poly[i][0] - poly[0][0], poly[i][1] - poly[0][1]};
        const double e2[2] = {poly[i + 1][0] - poly[0][0], poly[i + 1][1] - poly[0][1]};
        const double A = 0.5 * (e1[0] * e2[1] - e1[1] * e2[0]);
        if (!(A > 1e-15)) continue; /* a sliver of round-off */
        *covered += A;
        for (int q = 0; q < nq; q++, n++) {
            if (n >= cap) continue;
            xi[n][0] = poly[0][0] + rq[q][0] * e1[0] + rq[q][1] * e2[0];
            xi[n][1] = poly[0][1] + rq[q][0] * e1[1] + rq[q][1] * e2[1];
            w[n] = 2.0 * A * wq[q];
        }
    }
    if (n > cap) return FFC_ERR_CAPACITY;
    return (int)n;
}

/* Formulation (dual basis).  On a slave facet with the linear shape
 * functions N_a and the points xi_q, w_q of its segments (the covered part
 * only), M_ab = sum_q w_q N_a N_b and D = diag(sum_q w_q N_a).  The dual
 * functions Phi_a = sum_b A_ab N_b with A = D M^-1 satisfy
 *     sum_q w_q Phi_a N_b = delta_ab D_aa    (biorthogonality),
 * so that a multiplier field sum_a Phi_a lambda_a weighted by N_b gives
 * lambda_b D_bb: one node, one equation.  On a fully covered facet
 * A = [[3,-1,-1],[-1,3,-1],[-1,-1,3]] (Phi_a = 4 N_a - 1).  The area
 * element of a flat facet is constant and cancels in A.
 * Partly covered facets (over the rim of the master surface): the dual
 * basis of the covered part grows large where that part is thin (its M
 * nearly singular), and a switch to the standard basis at some coverage
 * would make the weights jump as the surfaces slide (measured: the
 * augmentations cycle).  So the basis is blended continuously,
 *     A = s D M^-1 + (1 - s) I,   s = clamp((f - 0.5) / 0.4, 0, 1),
 * f the covered fraction: dual from 90% coverage on, standard below 50%.
 * Both parts give sum_q w_q Phi_a = D_aa, so the nodal weights stay
 * positive.  A nearly singular M (det M below 1e-8 (tr M / 3)^3) keeps
 * A = I. */
int ffc_dual_basis(long n, const double xi[][2], const double w[], double A[3][3])
{
    if (!A) return FFC_ERR_NULL;
    memset(A, 0, 9 * sizeof(double));
    A[0][0] = A[1][1] = A[2][2] = 1.0;
    if (n < 0) return FFC_ERR_SIZE;
    if (n == 0) return FFC_OK;
    if (!xi || !w) return FFC_ERR_NULL;
    double M[3][3] = {{0}}, D[3] = {0}, cov = 0.0;
    for (long q = 0; q < n; q++) {
        cov += w[q];
        if (!isfinite(xi[q][0]) || !isfinite(xi[q][1]) || !isfinite(w[q])) return FFC_ERR_NONFINITE;
        const double N[3] = {1.0 - xi[q][0] - xi[q][1], xi[q][0], xi[q][1]};
        for (int a = 0; a < 3; a++) {
            D[a] += w[q] * N[a];
            for (int b = 0; b < 3; b++) M[a][b] += w[q] * N[a] * N[b];
        }
    }
    double C[3][3]; /* cofactors */
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
            const int a1 = (a + 1) % 3, a2 = (a + 2) % 3, b1 = (b + 1) % 3, b2 = (b + 2) % 3;
            C[a][b] = M[a1][b1] * M[a2][b2] - M[a1][b2] * M[a2][b1];
        }
    const double det = M[0][0] * C[0][0] + M[0][1] * C[0][1] + M[0][2] * C[0][2];
    const double tr = (M[0][0] + M[1][1] + M[2][2]) / 3.0;
    const double s = fmin(1.0, (2.0 * cov - 0.5) / (0.9 - 0.5)); /* covered fraction 2 cov: 0.5 -> 0, 0.9 -> 1 */
    if (!(s > 0.0) || !(det > 1e-8 * tr * tr * tr)) return FFC_OK;
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) A[a][b] = s * D[a] * C[b][a] / det + (1.0 - s) * (a == b); /* M^-1 = C^T / det */
    return FFC_OK;
}
