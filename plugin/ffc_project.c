/* ffc_project.c: closest-point projection of a point onto a 3- or 6-node
 * facet (safeguarded Newton, clamping onto edges and vertices) and the
 * derivatives of the foot, gap and normal with respect to nodal motion. */
#include "ffc.h"
#include "ffc_internal.h"

#include <math.h>
#include <string.h>

#define PROJ_MAXIT 50
#define INSIDE_TOL 1e-12   /* local-coordinate tolerance of "inside" */

/* x(xi), its first and second xi-derivatives for a facet. */
static void facet_eval(int nn, const double X[][3], const double xi[2],
                       double x[3], double t[2][3], double xx[3][3])
{
    double N[FFC_MAXNODES], dN[FFC_MAXNODES][2], d2N[FFC_MAXNODES][3];
    ffc_shape(nn, xi, N, dN);
    ffc_shape_d2(nn, xi, d2N);
    for (int i = 0; i < 3; i++) {
        x[i] = t[0][i] = t[1][i] = xx[0][i] = xx[1][i] = xx[2][i] = 0.0;
        for (int a = 0; a < nn; a++) {
            x[i] += N[a] * X[a][i];
            t[0][i] += dN[a][0] * X[a][i];
            t[1][i] += dN[a][1] * X[a][i];
            xx[0][i] += d2N[a][0] * X[a][i];
            xx[1][i] += d2N[a][1] * X[a][i];
            xx[2][i] += d2N[a][2] * X[a][i];
        }
    }
}

static double dist2(const double a[3], const double b[3])
{
    double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return ffc__dot(d, d);
}

/* The foot at xi: local coordinates, position, normal, gap and distance
 * of the projection record. */
static int set_foot(int nn, const double X[][3], const double p[3], const double xi[2], ffc_proj *out)
{
    ffc_point g;
    int st = ffc_facet_point(nn, X, xi, &g);
    if (st) return st;
    out->xi[0] = xi[0];
    out->xi[1] = xi[1];
    double r[3] = {p[0] - g.x[0], p[1] - g.x[1], p[2] - g.x[2]};
    for (int i = 0; i < 3; i++) {
        out->x[i] = g.x[i];
        out->n[i] = g.n[i];
    }
    out->gap = ffc__dot(g.n, r);
    out->dist = sqrt(ffc__dot(r, r));
    return FFC_OK;
}

/* Unconstrained stationary point of |p - x(xi)|^2 / 2 for a curved facet,
 * started at xi; Newton with the full Hessian when it is positive definite,
 * Gauss-Newton otherwise, and a backtracking line search. */
static int newton_free(int nn, const double X[][3], const double p[3],
                       double xi[2], int *iters, double h2)
{
    double x[3], t[2][3], xx[3][3], xt[3], tt[2][3], xxt[3][3];
    int have = 0; /* x, t, xx are those of xi (the last accepted trial's) */
    for (int it = 0; it < PROJ_MAXIT; it++) {
        if (!have) facet_eval(nn, X, xi, x, t, xx);
        double r[3] = {p[0] - x[0], p[1] - x[1], p[2] - x[2]};
        double F[2] = {-ffc__dot(t[0], r), -ffc__dot(t[1], r)};
        double m00 = ffc__dot(t[0], t[0]), m01 = ffc__dot(t[0], t[1]),
               m11 = ffc__dot(t[1], t[1]);
        double H00 = m00 - ffc__dot(r, xx[0]), H01 = m01 - ffc__dot(r, xx[1]),
               H11 = m11 - ffc__dot(r, xx[2]);
        double det = H00 * H11 - H01 * H01;
        if (!(H00 > 0.0 && det > 1e-8 * (m00 * m11 - m01 * m01))) {
            H00 = m00; H01 = m01; H11 = m11; /* Gauss-Newton safeguard */
            det = H00 * H11 - H01 * H01;
        }
        if (!(det > 0.0)) return FFC_ERR_DEGENERATE;
        double d[2] = {-(H11 * F[0] - H01 * F[1]) / det,
                       -(-H01 * F[0] + H00 * F[1]) / det};
        /* limit the step in local coordinates, then backtrack on the distance */
        double dn = fabs(d[0]) + fabs(d[1]);
        if (dn > 0.5) { d[0] *= 0.5 / dn; d[1] *= 0.5 / dn; }
        const double f0 = ffc__dot(r, r);
        double lam = 1.0, trial[2];
        for (int ls = 0; ls < 40; ls++) {
            trial[0] = xi[0] + lam * d[0];
            trial[1] = xi[1] + lam * d[1];
            facet_eval(nn, X, trial, xt, tt, xxt);
            if (dist2(p, xt) <= f0 * (1.0 + 1e-14) + 1e-30 * h2) break;
            /* near the solution the distance changes below its round-off:
             * accept a step that reduces the stationarity residual */
            double rt[3] = {p[0] - xt[0], p[1] - xt[1], p[2] - xt[2]};
            const double Ft0 = ffc__dot(tt[0], rt), Ft1 = ffc__dot(tt[1], rt);
            if (Ft0 * Ft0 + Ft1 * Ft1 < 0.25 * (F[0] * F[0] + F[1] * F[1])) break;
            lam *= 0.5;
        }
        xi[0] = trial[0];
        xi[1] = trial[1];
        *iters = it + 1;
        /* a step below 1e-13 of the coordinates (1 or more) is at round-off
         * after a quadratically converging sequence: converged, also outside
         * the neighbourhood below (a far point over a nearly flat facet) */
        if (lam * (fabs(d[0]) + fabs(d[1])) < 1e-13 * fmax(1.0, fabs(xi[0]) + fabs(xi[1]))) return FFC_OK;
        /* keep the iterate in a neighbourhood of the facet */
        have = !(xi[0] < -2.0 || xi[0] > 3.0 || xi[1] < -2.0 || xi[1] > 3.0);
        if (!have) {
            xi[0] = fmin(fmax(xi[0], -2.0), 3.0);
            xi[1] = fmin(fmax(xi[1], -2.0), 3.0);
        } else {
            memcpy(x, xt, sizeof x);
            memcpy(t, tt, sizeof t);
            memcpy(xx, xxt, sizeof xx);
        }
    }
    return FFC_ERR_NOCONV;
}

/* Closest point to p on edge e of the facet: the edge runs from vertex e
 * to vertex (e+1)%3; parameter s in [0,1].  Returns the squared distance. */
static double edge_min(int nn, const double X[][3], const double p[3], int e,
                       double *s_out)
{
    static const double V[3][2] = {{0, 0}, {1, 0}, {0, 1}};
    const double *A = V[e], *B = V[(e + 1) % 3];
    if (nn == 3) { /* straight edge: closed form */
        const double *a = X[e], *b = X[(e + 1) % 3];
        double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        double ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
        double l2 = ffc__dot(ab, ab), s = l2 > 0.0 ? ffc__dot(ap, ab) / l2 : 0.0;
        s = fmin(fmax(s, 0.0), 1.0);
        double q[3] = {a[0] + s * ab[0], a[1] + s * ab[1], a[2] + s * ab[2]};
        *s_out = s;
        return dist2(p, q);
    }
    double best_s = 0.0, best = INFINITY;
    double x[3], t[2][3], xx[3][3];
    /* coarse scan for the start, then 1D Newton with clamping */
    for (int k = 0; k <= 8; k++) {
        double s = k / 8.0, xi[2] = {A[0] + s * (B[0] - A[0]), A[1] + s * (B[1] - A[1])};
        facet_eval(nn, X, xi, x, t, xx);
        double d2 = dist2(p, x);
        if (d2 < best) { best = d2; best_s = s; }
    }
    const double e0 = B[0] - A[0], e1 = B[1] - A[1];
    double s = best_s;
    for (int it = 0; it < PROJ_MAXIT; it++) {
        double xi[2] = {A[0] + s * e0, A[1] + s * e1};
        facet_eval(nn, X, xi, x, t, xx);
        double xs[3], xss[3], r[3];
        for (int i = 0; i < 3; i++) {
            xs[i] = e0 * t[0][i] + e1 * t[1][i];
            xss[i] = e0 * e0 * xx[0][i] + 2.0 * e0 * e1 * xx[1][i] + e1 * e1 * xx[2][i];
            r[i] = x[i] - p[i];
        }
        double g = ffc__dot(xs, r), H = ffc__dot(xs, xs) + ffc__dot(xss, r);
        if (!(H > 0.0)) H = ffc__dot(xs, xs);
        if (!(H > 0.0)) break;
        double sn = fmin(fmax(s - g / H, 0.0), 1.0);
        if (fabs(sn - s) < 1e-15) { s = sn; break; }
        s = sn;
    }
    double xi[2] = {A[0] + s * e0, A[1] + s * e1};
    facet_eval(nn, X, xi, x, t, xx);
    double d2 = dist2(p, x);
    if (d2 <= best) { best = d2; best_s = s; }
    *s_out = best_s;
    return best;
}

/* Unconstrained stationary point of |p - x(xi)| (the foot on the facet's
 * extension); fills xi = xi_free, the foot, normal and gap at it, and
 * where = FFC_FOOT_INSIDE. */
int ffc__project_free(int nn, const double X[][3], const double p[3], ffc_proj *out)
{
    return ffc__project_free_from(nn, X, p, NULL, out);
}

int ffc__project_free_from(int nn, const double X[][3], const double p[3], const double xi0[2], ffc_proj *out)
{
    if (!X || !p || !out) return FFC_ERR_NULL;
    if (nn != 3 && nn != 6) return FFC_ERR_NODES;
    for (int i = 0; i < 3; i++)
        if (!isfinite(p[i])) return FFC_ERR_NONFINITE;
    for (int a = 0; a < nn; a++)
        for (int i = 0; i < 3; i++)
            if (!isfinite(X[a][i])) return FFC_ERR_NONFINITE;

    /* flat solution on the vertex triangle: exact for 3 nodes, the start
     * for 6 nodes */
    double t0[3], t1[3], r0[3];
    for (int i = 0; i < 3; i++) {
        t0[i] = X[1][i] - X[0][i];
        t1[i] = X[2][i] - X[0][i];
        r0[i] = p[i] - X[0][i];
    }
    /* with c = t0 x t1: xi = ((r0 x t1) . c, (t0 x r0) . c) / |c|^2, free
     * of the cancellation in m00 m11 - m01^2 for slivers */
    double c[3], a[3], b[3];
    ffc__cross(t0, t1, c);
    const double det = ffc__dot(c, c);
    const double h2 = ffc__facet_size2(X);
    if (ffc__degenerate(det, h2)) return FFC_ERR_DEGENERATE;
    ffc__cross(r0, t1, a);
    ffc__cross(t0, r0, b);
    double xi[2] = {ffc__dot(a, c) / det, ffc__dot(b, c) / det};
    out->iters = 0;
    if (nn == 6) {
        if (xi0 && isfinite(xi0[0]) && isfinite(xi0[1])) {
            xi[0] = xi0[0];
            xi[1] = xi0[1];
        }
        int st = newton_free(nn, X, p, xi, &out->iters, h2);
        if (st) return st;
    }
    out->xi_free[0] = xi[0];
    out->xi_free[1] = xi[1];
    out->where = FFC_FOOT_INSIDE;
    return set_foot(nn, X, p, xi, out);
}

int ffc_project(int nn, const double X[][3], const double p[3], ffc_proj *out)
{
    int st0 = ffc__project_free(nn, X, p, out);
    if (st0) return st0;
    double xi[2] = {out->xi_free[0], out->xi_free[1]};
    int status = FFC_OK;
    out->where = FFC_FOOT_INSIDE;
    if (xi[0] < -INSIDE_TOL || xi[1] < -INSIDE_TOL || xi[0] + xi[1] > 1.0 + INSIDE_TOL) {
        /* the foot left the facet: closest point on its boundary */
        int be = 0;
        double bs = 0.0, bd = INFINITY;
        for (int e = 0; e < 3; e++) {
            double s, d2 = edge_min(nn, X, p, e, &s);
            if (d2 < bd) { bd = d2; bs = s; be = e; }
        }
        static const double V[3][2] = {{0, 0}, {1, 0}, {0, 1}};
        const double *A = V[be], *B = V[(be + 1) % 3];
        if (bs <= 0.0) {
            out->where = FFC_FOOT_VERTEX0 + be;
            status = FFC_INFO_VERTEX;
            xi[0] = A[0]; xi[1] = A[1];
        } else if (bs >= 1.0) {
            out->where = FFC_FOOT_VERTEX0 + (be + 1) % 3;
            status = FFC_INFO_VERTEX;
            xi[0] = B[0]; xi[1] = B[1];
        } else {
            out->where = FFC_FOOT_EDGE0 + be;
            status = FFC_INFO_EDGE;
            xi[0] = A[0] + bs * (B[0] - A[0]);
            xi[1] = A[1] + bs * (B[1] - A[1]);
        }
    }
    int st = set_foot(nn, X, p, xi, out);
    return st ? st : status;
}

/* Formulation: the foot xi of p on the master facet solves
 *   F_a(xi, u) = tau_a . (x(xi) - p) = 0,   a = 1, 2.
 * With r = p - x, its total variation gives
 *   A_ab dxi_b = tau_a . dp - tau_a . sum_b N_b du_b + r . sum_b N_b,a du_b,
 *   A_ab = m_ab - r . x_,ab,
 * where dp = sum_c Ns_c du_c (slave nodes) and du_b are master nodal
 * motions.  The gap g = n . r varies as dg = n . (dp - sum_b N_b du_b)
 * (r is parallel to n and dn is orthogonal to it; tau_a . r = 0).
 * The unit normal varies in the tangent plane:
 *   dn = -tau^a (n . dtau_a),  dtau_a = sum_b N_b,a du_b + x_,ab dxi_b,
 * with tau^a = m^ab tau_b the contravariant tangents. */
int ffc_project_deriv(int ns, const double Ns[], int nm, const double Xm[][3],
                      const ffc_proj *pr, double dxi[2][FFC_MAXDOF],
                      double dg[FFC_MAXDOF], double dn[3][FFC_MAXDOF])
{
    if (!Ns || !Xm || !pr || !dxi || !dg || !dn) return FFC_ERR_NULL;
    if (ns < 1 || ns > FFC_MAXNODES) return FFC_ERR_SIZE;
    if (nm != 3 && nm != 6) return FFC_ERR_NODES;
    if (pr->where != FFC_FOOT_INSIDE) return FFC_ERR_VALUE;

    double N[FFC_MAXNODES], dN[FFC_MAXNODES][2];
    double x[3], t[2][3], xx[3][3];
    ffc_shape(nm, pr->xi, N, dN);
    facet_eval(nm, Xm, pr->xi, x, t, xx);
    ffc_point g;
    int st = ffc_facet_point(nm, Xm, pr->xi, &g);
    if (st) return st;
    const double *n = g.n;
    /* r = p - x = gap n at an interior foot */
    double r[3] = {pr->gap * n[0], pr->gap * n[1], pr->gap * n[2]};
    double A00 = g.m[0][0] - ffc__dot(r, xx[0]), A01 = g.m[0][1] - ffc__dot(r, xx[1]),
           A11 = g.m[1][1] - ffc__dot(r, xx[2]);
    double det = A00 * A11 - A01 * A01;
    if (!(fabs(det) > 1e-14 * g.j * g.j)) return FFC_ERR_DEGENERATE;
    const double Ai[2][2] = {{A11 / det, -A01 / det}, {-A01 / det, A00 / det}};
    /* contravariant tangents */
    double tc[2][3];
    for (int i = 0; i < 3; i++) {
        tc[0][i] = g.minv[0][0] * t[0][i] + g.minv[0][1] * t[1][i];
        tc[1][i] = g.minv[1][0] * t[0][i] + g.minv[1][1] * t[1][i];
    }
    const double nxx[2][2] = {{ffc__dot(n, xx[0]), ffc__dot(n, xx[1])},
                              {ffc__dot(n, xx[1]), ffc__dot(n, xx[2])}};
    const int nd = 3 * (ns + nm);
    for (int k = 0; k < nd; k++) {
        const int slave = k < 3 * ns;
        const int node = slave ? k / 3 : (k - 3 * ns) / 3, c = k % 3;
        /* right-hand side b_a of A dxi = b for a unit motion of dof k */
        double b[2];
        for (int a = 0; a < 2; a++)
            b[a] = slave ? t[a][c] * Ns[node]
                         : -t[a][c] * N[node] + r[c] * dN[node][a];
        const double d0 = Ai[0][0] * b[0] + Ai[0][1] * b[1];
        const double d1 = Ai[1][0] * b[0] + Ai[1][1] * b[1];
        dxi[0][k] = d0;
        dxi[1][k] = d1;
        dg[k] = slave ? Ns[node] * n[c] : -N[node] * n[c];
        /* n . dtau_a */
        double ndt[2];
        for (int a = 0; a < 2; a++)
            ndt[a] = (slave ? 0.0 : dN[node][a] * n[c]) + nxx[a][0] * d0 + nxx[a][1] * d1;
        for (int i = 0; i < 3; i++)
            dn[i][k] = -(tc[0][i] * ndt[0] + tc[1][i] * ndt[1]);
    }
    return FFC_OK;
}
