/* ffc_normal.c: augmented-Lagrangian normal contact of one link: the link
 * geometry (gap, foot, area and their derivatives), residual and consistent
 * tangent, with the friction terms of ffc_friction.c. */
#include "ffc.h"
#include "ffc_internal.h"
#include "ffc_link_internal.h"

#include <math.h>
#include <string.h>

/* Geometry of one link: slave point, foot, gap g, point area da and
 *   G[nd]      = dg/du = [N1_a n ; -N2_b(xi) n]
 *   dda[nd]    = d da / du (slave dofs; zero with small strain)
 *   D[nd][nd]  = dG/du (when D != NULL):
 *     slave rows  a,c:  N1_a dn_c/du
 *     master rows b,c: -N2_b dn_c/du - n_c N2_b,alpha dxi_alpha/du
 * with dn/du and dxi/du from ffc_project_deriv (the variation of the
 * master normal and the sliding of the foot), and
 *     d da / d x_a = w J N1_a,alpha tau^alpha
 * when the area element follows the deformation (finite_def).
 * A rigid obstacle as the master (ob, nm = 0): g = phi(x_s), n = grad phi
 * and H = dn/dx from ffc_obstacle_gap, so that with x_s = sum_a N1_a x_a
 *     G[3a+i] = N1_a n_i,  dn_i/du_{3b+j} = H_ij N1_b,
 *     D[3a+i][3b+j] = N1_a N1_b H_ij
 * exactly (no foot sliding: the obstacle has no unknowns). */
static int obstacle_geometry(const ffc_obstacle *ob, int ns, const double p[3], ffc_link_state *st, lgeo_t *g,
                             double D[FFC_MAXDOF][FFC_MAXDOF])
{
    double n[3], H[3][3], gap;
    int s = ffc_obstacle_gap(ob, p, &gap, n, H);
    if (s) return s;
    const int nd = 3 * ns;
    for (int i = 0; i < 3; i++) { st->n[i] = n[i]; g->dm[i] = ob->d[i]; }
    st->gap = gap;
    for (int a = 0; a < ns; a++)
        for (int i = 0; i < 3; i++) {
            g->G[3 * a + i] = g->N1[a] * n[i];
            for (int j = 0; j < 3; j++) g->dn[i][3 * a + j] = H[i][j] * g->N1[a];
        }
    for (int k = 0; k < nd; k++) g->dxi[0][k] = g->dxi[1][k] = 0.0;
    if (D)
        for (int k = 0; k < nd; k++)
            for (int l = 0; l < nd; l++) D[k][l] = g->N1[k / 3] * g->dn[k % 3][l];
    return FFC_OK;
}

int ffc__link_geometry(const ffc_effects *fx, int ns, const double Xs[][3], const double Xs0[][3],
                       const double xs[2], double w, int nm, const double Xm[][3], const double xm0[2],
                       const ffc_obstacle *ob, ffc_link_state *st, lgeo_t *g, double D[FFC_MAXDOF][FFC_MAXDOF])
{
    const int nd = 3 * (ns + nm);
    g->ns = ns;
    g->nm = nm;
    g->nd = nd;
    double dN1[FFC_MAXNODES][2];
    int s = ffc_shape(ns, xs, g->N1, dN1);
    if (s) return s;
    double p[3] = {0, 0, 0};
    for (int a = 0; a < ns; a++)
        for (int i = 0; i < 3; i++) p[i] += g->N1[a] * Xs[a][i];
    ffc_point sp;
    s = ffc_facet_point(ns, fx->finite_def ? Xs : Xs0, xs, &sp);
    if (s) return s;
    memset(st, 0, sizeof *st);
    for (int i = 0; i < 3; i++) { st->x[i] = p[i]; g->dm[i] = 0.0; }
    st->da = w * sp.j;
    for (int k = 0; k < nd; k++) g->dda[k] = 0.0;
    ffc_proj pr;
    if (ob) {
        if (nm != 0) return FFC_ERR_NODES;
        s = obstacle_geometry(ob, ns, p, st, g, D);
        if (s) return s;
    } else {
        s = ffc__project_free_from(nm, Xm, p, xm0, &pr);
        if (s) return s;
        for (int i = 0; i < 3; i++) st->n[i] = pr.n[i];
        st->xi[0] = pr.xi[0];
        st->xi[1] = pr.xi[1];
        st->gap = pr.gap;
        s = ffc_project_deriv(ns, g->N1, nm, Xm, &pr, g->dxi, g->G, g->dn);
        if (s) return s;
        ffc_shape(nm, pr.xi, g->N2, g->dN2);
    }
    if (fx->finite_def) {
        double tc[2][3];
        for (int i = 0; i < 3; i++) {
            tc[0][i] = sp.minv[0][0] * sp.tau[0][i] + sp.minv[0][1] * sp.tau[1][i];
            tc[1][i] = sp.minv[1][0] * sp.tau[0][i] + sp.minv[1][1] * sp.tau[1][i];
        }
        for (int a = 0; a < ns; a++)
            for (int i = 0; i < 3; i++)
                g->dda[3 * a + i] = w * sp.j * (dN1[a][0] * tc[0][i] + dN1[a][1] * tc[1][i]);
    }
    if (!D || ob) return FFC_OK;
    for (int k = 0; k < nd; k++) {
        const int slave = k < 3 * ns, c = k % 3;
        const int node = slave ? k / 3 : (k - 3 * ns) / 3;
        for (int l = 0; l < nd; l++)
            D[k][l] = slave ? g->N1[node] * g->dn[c][l]
                            : -g->N2[node] * g->dn[c][l] -
                                  pr.n[c] * (g->dN2[node][0] * g->dxi[0][l] + g->dN2[node][1] * g->dxi[1][l]);
    }
    return FFC_OK;
}

/* Formulation (frictionless, pointwise; gap g = n . (x_s - x_m) >= 0 open).
 * A link is a slave point x_s = sum_a N1_a(xs) x_a with area da = w J_s,
 * and its foot xi on the master facet: tau_a(xi) . (x_s - x_m(xi)) = 0.
 * Pressure t_N = <lambda - eps g>.  The virtual work of the contact
 * traction, da t_N dg, gives the internal-force residual
 *     R = -da t_N G
 * (the traction t_N n pushes the slave out along the master normal).
 * Its derivative, with dt_N = -eps H(t_N) G . du:
 *     K = da eps G G^T  -  da t_N D  -  t_N G dda^T
 * with G, D, dda from ffc__link_geometry.  With friction,
 * ffc__link_friction adds its terms and the coupling
 * F (dt_N/du)^T = -eps F G^T. */
int ffc__link_contact(const ffc_effects *effects, int ns, const double Xs[][3], const double Xs0[][3],
                      const double Ds[][3], const double xs[2], double w, int nm, const double Xm[][3],
                      const double Dm[][3], const ffc_obstacle *ob, double lambda, const double lam_t[3],
                      const ffc_law *law, ffc_link_state *st, double R[FFC_MAXDOF], double K[FFC_MAXDOF][FFC_MAXDOF])
{
    if (!effects || !Xs || !Xs0 || !xs || (!Xm && !ob) || !st || !R || !law) return FFC_ERR_NULL;
    if ((ns != 3 && ns != 6) || (ob ? nm != 0 : nm != 3 && nm != 6)) return FFC_ERR_NODES;
    const double eps = law->eps_n;
    if (!(eps > 0) || isinf(eps) || !isfinite(lambda) || !(w > 0)) return FFC_ERR_VALUE;
    const int fric = ffc__friction_on(effects, law);
    if (fric && (!Ds || (!Dm && !ob) || !lam_t)) return FFC_ERR_NULL;
    if (fric && effects->dynamic && !ffc__dynamic_ok(law)) return FFC_ERR_VALUE;
    const int nd = 3 * (ns + nm);
    for (int k = 0; k < nd; k++) R[k] = 0.0;
    if (K)
        for (int k = 0; k < nd; k++) memset(K[k], 0, (size_t)nd * sizeof K[k][0]);
    lgeo_t g;
    int s = ffc__link_geometry(effects, ns, Xs, Xs0, xs, w, nm, Xm, NULL, ob, st, &g, K && !ffc__law_material(law) ? K : NULL);
    if (s) return s;
    const double trial = lambda - eps * st->gap;
    st->active = trial > 0.0;
    st->tn = st->active ? trial : 0.0;
    if (!st->active) {
        if (K)
            for (int k = 0; k < nd; k++) memset(K[k], 0, (size_t)nd * sizeof K[k][0]);
        return FFC_OK;
    }
    const double da = st->da, tn = st->tn;
    for (int k = 0; k < nd; k++) R[k] = -da * tn * g.G[k];
    if (K) {
        /* K holds D on entry (consistent tangent) or zero (material only) */
        for (int k = 0; k < nd; k++)
            for (int l = 0; l < nd; l++)
                K[k][l] = ffc__law_material(law) ? da * eps * g.G[k] * g.G[l]
                                             : da * (eps * g.G[k] * g.G[l] - tn * K[k][l]) - tn * g.G[k] * g.dda[l];
    }
    if (!fric) return FFC_OK;
    double r[3];
    ffc__link_slip(&g, Ds, Dm, r);
    ffc_fric f;
    s = ffc_friction_map(st->n, lam_t, r, law->mu, law->eps_t, tn, &f);
    if (s) return s;
    const double sc = ffc__slip_scale(effects, law);
    for (int i = 0; i < 3; i++) { st->t[i] = f.t[i]; st->slip[i] = sc * r[i]; }
    st->fstate = f.state;
    double F[FFC_MAXDOF];
    ffc__link_friction(&g, st, Dm, ffc__motion_coef(effects, law), &f, ffc__law_material(law), R, K, F);
    if (K)
        for (int k = 0; k < nd; k++)
            for (int l = 0; l < nd; l++) K[k][l] -= eps * F[k] * g.G[l];
    return FFC_OK;
}

int ffc_link_contact(const ffc_effects *effects, int ns, const double Xs[][3],
                     const double Xs0[][3], const double Ds[][3], const double xs[2],
                     double w, int nm, const double Xm[][3], const double Dm[][3],
                     double lambda, const double lam_t[3], const ffc_law *law,
                     ffc_link_state *st, double R[FFC_MAXDOF],
                     double K[FFC_MAXDOF][FFC_MAXDOF])
{
    if (!Xm) return FFC_ERR_NULL;
    return ffc__link_contact(effects, ns, Xs, Xs0, Ds, xs, w, nm, Xm, Dm, NULL, lambda, lam_t, law, st, R, K);
}

int ffc_link_obstacle(const ffc_effects *effects, int ns, const double Xs[][3], const double Xs0[][3],
                      const double Ds[][3], const double xs[2], double w, const ffc_obstacle *ob, double lambda,
                      const double lam_t[3], const ffc_law *law, ffc_link_state *st, double R[FFC_MAXDOF],
                      double K[FFC_MAXDOF][FFC_MAXDOF])
{
    if (!ob) return FFC_ERR_NULL;
    int s = ffc_obstacle_check(ob);
    if (s) return s;
    return ffc__link_contact(effects, ns, Xs, Xs0, Ds, xs, w, 0, NULL, NULL, ob, lambda, lam_t, law, st, R, K);
}

int ffc_link_normal(const ffc_effects *effects, int ns, const double Xs[][3],
                    const double Xs0[][3], const double xs[2], double w,
                    int nm, const double Xm[][3], double lambda, double eps,
                    ffc_link_state *st, double R[FFC_MAXDOF],
                    double K[FFC_MAXDOF][FFC_MAXDOF])
{
    if (!effects) return FFC_ERR_NULL;
    ffc_effects fx = *effects;
    fx.friction = 0;
    ffc_law law = {eps, 0, 0, 0.0, 0.0, 0.0, 0.0, NULL, NULL, 0, NULL, 0, NULL, NULL, NULL};
    return ffc_link_contact(&fx, ns, Xs, Xs0, NULL, xs, w, nm, Xm, NULL, lambda, NULL, &law, st, R, K);
}
