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
 * fully covered facet sum to 1/2, as the facet's own rule does.
 *
 * Formulation (the segment's motion).  An integral over the segment,
 * I = int_S F dxi, changes with the nodal positions u through F and
 * through S (Reynolds):  dI = int_S dF dxi + oint F (v . nu) ds, with nu
 * the outward normal of S and v the velocity of its boundary.  Edges on
 * the slave triangle's sides do not move (v . nu = 0); an edge on the
 * projected master edge A_j A_k moves with it: at the point A_j +
 * s (A_k - A_j) of that line, v = (1 - s) dA_j + s dA_k, and each
 * projected vertex moves as
 *     dxi = m^-1 (dr - dm xi),  r_a = t_a . (y - s_0),  m_ab = t_a . t_b,
 * with dt_1 = ds_1 - ds_0, dt_2 = ds_2 - ds_0, d(y - s_0) = dy - ds_0.  Each
 * moving edge gets the Gauss rule exact to degree qdeg + 1 (F of degree
 * qdeg times the linear v . nu; 2 points for qdeg 2); at its point b,
 * edv[b][l] is omega_b L (nu . v) per unit change of dof l (dofs: the
 * slave facet's three nodes, then the master facet's, x, y, z each), so
 * that oint F (v . nu) ds = sum_b F(exi_b) edv[b][.].  This is the exact
 * derivative of the residual's sum over the points when the rules are
 * exact for F: always on linear facets with qdeg >= 2 (F is a product of
 * linear functions there), on straight-sided 6-node facets with qdeg >= 3;
 * on curved facets the two differ by the rules' error. */
static void vertex_motion(const double t[2][3], const double mt[2][2], double det, const double d[3],
                          const double xi[2], int b, double dA[2][18])
{
    for (int l = 0; l < 18; l++) {
        const int node = l / 3, c = l % 3;
        double dt[2][3] = {{0, 0, 0}, {0, 0, 0}}, dd[3] = {0, 0, 0};
        if (node == 0) { dt[0][c] = dt[1][c] = -1.0; dd[c] = -1.0; }
        else if (node == 1) dt[0][c] = 1.0;
        else if (node == 2) dt[1][c] = 1.0;
        else if (node - 3 == b) dd[c] = 1.0;
        else { dA[0][l] = dA[1][l] = 0.0; continue; }
        double rhs[2];
        for (int a = 0; a < 2; a++) {
            rhs[a] = ffc__dot(dt[a], d) + ffc__dot(t[a], dd);
            for (int e = 0; e < 2; e++) rhs[a] -= (ffc__dot(dt[a], t[e]) + ffc__dot(t[a], dt[e])) * xi[e];
        }
        dA[0][l] = (mt[1][1] * rhs[0] - mt[0][1] * rhs[1]) / det;
        dA[1][l] = (mt[0][0] * rhs[1] - mt[1][0] * rhs[0]) / det;
    }
}

/* |line (a, b) at p| / |b - a|: the distance of p from the line through a, b */
static double line_dist(const double a[2], const double b[2], const double p[2])
{
    const double ex = b[0] - a[0], ey = b[1] - a[1];
    return fabs(ex * (p[1] - a[1]) - ey * (p[0] - a[0])) / sqrt(ex * ex + ey * ey);
}

int ffc_mortar_segment(int qdeg, const double Xs[3][3], const double Xm[3][3], long cap, double xi[][2],
                       double w[], long ecap, double exi[][2], double edv[][18], long *ne, double *covered)
{
    if (ne) *ne = 0;
    if (!Xs || !Xm || !xi || !w || !covered || (exi && (!edv || !ne))) return FFC_ERR_NULL;
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
    if (ffc__degenerate(det, mt[0][0] + mt[1][1])) return FFC_ERR_DEGENERATE;
    double pm[3][2], dm[3][3];
    int ord[3] = {0, 1, 2}; /* master vertex of each corner of pm */
    for (int b = 0; b < 3; b++) {
        for (int i = 0; i < 3; i++) dm[b][i] = Xm[b][i] - Xs[0][i];
        const double r0 = ffc__dot(t[0], dm[b]), r1 = ffc__dot(t[1], dm[b]);
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
        ord[1] = 2;
        ord[2] = 1;
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
    if (!exi) return (int)n;
    /* the moving edges: on a master edge line, not on a side of the slave triangle */
    double dA[3][2][18];
    for (int c = 0; c < 3; c++) vertex_motion((const double(*)[3])t, (const double(*)[2])mt, det, dm[ord[c]], pm[c],
                                              ord[c], dA[c]);
    /* the edge rule: Gauss-Legendre on [0, 1] exact to degree qdeg + 1 (the integrand's degree and
       the velocity's one): 2 points for qdeg <= 2, 3 for 3-4, 4 for 5-6 */
    static const double gx[3][4] = {{0.21132486540518713, 0.78867513459481287},
                                    {0.11270166537925831, 0.5, 0.88729833462074169},
                                    {0.069431844202973713, 0.33000947820757187, 0.66999052179242813,
                                     0.93056815579702629}};
    static const double gw[3][4] = {{0.5, 0.5},
                                    {0.27777777777777778, 0.44444444444444444, 0.27777777777777778},
                                    {0.17392742256872693, 0.32607257743127307, 0.32607257743127307,
                                     0.17392742256872693}};
    const int rule = qdeg <= 2 ? 0 : qdeg <= 4 ? 1 : 2, ng = rule + 2;
    const double *gs = gx[rule], *gsw = gw[rule];
    const double tol = 1e-10;
    long m = 0;
    for (int i = 0; i < np; i++) {
        const double *P = poly[i], *Q = poly[(i + 1) % np];
        if ((fabs(P[1]) <= tol && fabs(Q[1]) <= tol) || (fabs(P[0]) <= tol && fabs(Q[0]) <= tol) ||
            (fabs(P[0] + P[1] - 1.0) <= tol && fabs(Q[0] + Q[1] - 1.0) <= tol))
            continue;
        int j = -1;
        for (int c = 0; c < 3 && j < 0; c++)
            if (line_dist(pm[c], pm[(c + 1) % 3], P) <= tol && line_dist(pm[c], pm[(c + 1) % 3], Q) <= tol) j = c;
        if (j < 0) continue; /* (round-off: an edge of neither) */
        const int k = (j + 1) % 3;
        const double ex = Q[0] - P[0], ey = Q[1] - P[1], L = sqrt(ex * ex + ey * ey);
        if (!(L > 1e-14)) continue;
        const double nu[2] = {ey / L, -ex / L}; /* outward: the polygon is counter-clockwise */
        const double ax = pm[k][0] - pm[j][0], ay = pm[k][1] - pm[j][1], al2 = ax * ax + ay * ay;
        for (int g = 0; g < ng; g++, m++) {
            if (m >= ecap) continue;
            exi[m][0] = P[0] + gs[g] * ex;
            exi[m][1] = P[1] + gs[g] * ey;
            const double s = ((exi[m][0] - pm[j][0]) * ax + (exi[m][1] - pm[j][1]) * ay) / al2;
            for (int l = 0; l < 18; l++)
                edv[m][l] = gsw[g] * L * (nu[0] * ((1 - s) * dA[j][0][l] + s * dA[k][0][l]) +
                                       nu[1] * ((1 - s) * dA[j][1][l] + s * dA[k][1][l]));
        }
    }
    *ne = m;
    if (m > ecap) return FFC_ERR_CAPACITY;
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
void ffc__dual_add(ffc__dual_moments *m, const double xi[2], double w)
{
    const double N[3] = {1.0 - xi[0] - xi[1], xi[0], xi[1]};
    m->c += w;
    for (int a = 0; a < 3; a++) {
        m->D[a] += w * N[a];
        for (int b = 0; b < 3; b++) m->M[a][b] += w * N[a] * N[b];
    }
}

double ffc__dual_blend(const ffc__dual_moments *m, double Mi[3][3])
{
    double C[3][3]; /* cofactors */
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
            const int a1 = (a + 1) % 3, a2 = (a + 2) % 3, b1 = (b + 1) % 3, b2 = (b + 2) % 3;
            C[a][b] = m->M[a1][b1] * m->M[a2][b2] - m->M[a1][b2] * m->M[a2][b1];
        }
    const double det = m->M[0][0] * C[0][0] + m->M[0][1] * C[0][1] + m->M[0][2] * C[0][2];
    const double tr = (m->M[0][0] + m->M[1][1] + m->M[2][2]) / 3.0;
    const double s = fmin(1.0, (2.0 * m->c - 0.5) / (0.9 - 0.5)); /* covered fraction 2 c: 0.5 -> 0, 0.9 -> 1 */
    if (!(s > 0.0) || !(det > 1e-8 * tr * tr * tr)) return 0.0;
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) Mi[a][b] = C[b][a] / det; /* M^-1 = C^T / det */
    return s;
}

void ffc__dual_matrix(const ffc__dual_moments *m, double A[3][3])
{
    double Mi[3][3];
    const double s = ffc__dual_blend(m, Mi);
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) A[a][b] = (s > 0.0 ? s * m->D[a] * Mi[a][b] : 0.0) + (1.0 - s) * (a == b);
}

int ffc_dual_basis(long n, const double xi[][2], const double w[], double A[3][3])
{
    if (!A) return FFC_ERR_NULL;
    memset(A, 0, 9 * sizeof(double));
    A[0][0] = A[1][1] = A[2][2] = 1.0;
    if (n < 0) return FFC_ERR_SIZE;
    if (n == 0) return FFC_OK;
    if (!xi || !w) return FFC_ERR_NULL;
    ffc__dual_moments m;
    memset(&m, 0, sizeof m);
    for (long q = 0; q < n; q++) {
        if (!isfinite(xi[q][0]) || !isfinite(xi[q][1]) || !isfinite(w[q])) return FFC_ERR_NONFINITE;
        ffc__dual_add(&m, xi[q], w[q]);
    }
    ffc__dual_matrix(&m, A);
    return FFC_OK;
}

int ffc_mortar_links(int nn, long nfs, const long Fs[], long nfm, const long Fm[], long nvs, const double x[], int qdeg,
                     long npairs, const long pairs[], long lcap, ffc_link links[], long *lneed, long ecap,
                     ffc_mortar_edge edges[], long *eneed)
{
    long d1, d2;
    if (!lneed) lneed = &d1;
    if (!eneed) eneed = &d2;
    *lneed = *eneed = 0;
    if (!Fs || !Fm || !x || (npairs > 0 && !pairs) || (lcap > 0 && !links) || (ecap > 0 && !edges)) return FFC_ERR_NULL;
    if (nn != 3 && nn != 6) return FFC_ERR_NODES;
    if (nfs <= 0 || nfm <= 0 || npairs < 0 || lcap < 0 || ecap < 0) return FFC_ERR_SIZE;
    if (ffc_quad_size(qdeg) < 0) return FFC_ERR_QUAD;
    long n = 0, m = 0;
    double xi[96][2], w[96], exi[12][2], edv[12][18]; /* (at most 3 moving edges of 4 points) */
    for (long k = 0; k < npairs; k++) {
        const long f = pairs[2 * k], g = pairs[2 * k + 1];
        if (f < 0 || f >= nfs || g < 0 || g >= nfm) { *lneed = k; return FFC_ERR_INDEX; }
        double Xs[FFC_MAXNODES][3], Xm[FFC_MAXNODES][3];
        for (int a = 0; a < nn; a++) {
            const long vs = Fs[nn * f + a], vm = Fm[nn * g + a];
            if (vs < 0 || vs >= nvs || vm < 0 || vm >= nvs) { *lneed = k; return FFC_ERR_INDEX; }
            for (int i = 0; i < 3; i++) {
                Xs[a][i] = x[3 * vs + i];
                Xm[a][i] = x[3 * vm + i];
            }
        }
        double cov;
        long ne = 0;
        /* (6-node facets: the segments of the vertex triangles, their first 3 nodes; their edge points
           always, for the check below) */
        const int np = ffc_mortar_segment(qdeg, (const double(*)[3])Xs, (const double(*)[3])Xm, 96, xi, w, 12,
                                          edges || nn == 6 ? exi : NULL, edv, &ne, &cov);
        if (np < 0) return np;
        /* each point's foot on the master facet (the closest point); on a curved 6-node facet a
           point far off it may have none in the facet's neighbourhood (FFC_ERR_NOCONV): such a
           pair, far out of contact, gives no segment (whether the tangent's edge points are asked
           for or not: those are checked too) */
        ffc_proj pr[96];
        int far = 0;
        for (int q = 0; q < np + (nn == 6 ? (int)ne : 0) && !far; q++) {
            const double *z = q < np ? xi[q] : exi[q - np];
            double N[FFC_MAXNODES], p[3] = {0, 0, 0};
            ffc_shape(nn, z, N, NULL);
            for (int a = 0; a < nn; a++)
                for (int i = 0; i < 3; i++) p[i] += N[a] * Xs[a][i];
            ffc_proj e;
            const int st = ffc__project_free(nn, (const double(*)[3])Xm, p, q < np ? &pr[q] : &e);
            if (st == FFC_ERR_NOCONV && nn == 6) far = 1;
            else if (st < 0) return st;
        }
        if (far) continue;
        for (int q = 0; q < np; q++, n++) {
            if (n >= lcap) continue;
            ffc_link *lk = &links[n];
            lk->sf = f;
            lk->q = -1;
            lk->xs[0] = xi[q][0];
            lk->xs[1] = xi[q][1];
            lk->w = w[q];
            lk->mf = g;
            lk->xm[0] = pr[q].xi[0];
            lk->xm[1] = pr[q].xi[1];
            lk->gap = pr[q].gap;
            for (int i = 0; i < 3; i++) lk->n[i] = pr[q].n[i];
            lk->where = FFC_FOOT_INSIDE;
        }
        for (long b = 0; edges && np > 0 && b < ne; b++, m++) {
            if (m >= ecap) continue;
            edges[m].sf = f;
            edges[m].mf = g;
            edges[m].xs[0] = exi[b][0];
            edges[m].xs[1] = exi[b][1];
            /* the vertices' dofs in the link's order: the slave facet's nn nodes, then the master's */
            memset(edges[m].dv, 0, sizeof edges[m].dv);
            for (int l = 0; l < 9; l++) {
                edges[m].dv[l] = edv[b][l];
                edges[m].dv[3 * nn + l] = edv[b][9 + l];
            }
        }
    }
    *lneed = n;
    *eneed = m;
    if (n > lcap || m > ecap) return FFC_ERR_CAPACITY;
    return n <= 2147483647L ? (int)n : FFC_ERR_SIZE;
}
