/* ffc_link.c: augmented-Lagrangian normal contact: residual and consistent
 * tangent of one link, assembly over all links, Uzawa update and per-point
 * output. */
#include "ffc.h"
#include "ffc_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Geometry of one link, everything the normal and frictional terms need. */
typedef struct {
    int ns, nm, nd;                 /* slave, master nodes; unknowns 3 (ns + nm) */
    double N1[FFC_MAXNODES];        /* slave shape values at the point */
    double N2[FFC_MAXNODES];        /* master shape values at the foot */
    double dN2[FFC_MAXNODES][2];    /* their derivatives d N2_b / d xi_alpha */
    double dxi[2][FFC_MAXDOF];      /* d xi_alpha / du (sliding of the foot) */
    double dn[3][FFC_MAXDOF];       /* d n_i / du (turning of the normal) */
    double G[FFC_MAXDOF];           /* dg / du */
    double dda[FFC_MAXDOF];         /* d da / du (zero with small strain) */
} lgeo_t;

/* Geometry of one link: slave point, foot, gap g, point area da and
 *   G[nd]      = dg/du = [N1_a n ; -N2_b(xi) n]
 *   dda[nd]    = d da / du (slave dofs; zero with small strain)
 *   D[nd][nd]  = dG/du (when D != NULL):
 *     slave rows  a,c:  N1_a dn_c/du
 *     master rows b,c: -N2_b dn_c/du - n_c N2_b,alpha dxi_alpha/du
 * with dn/du and dxi/du from ffc_project_deriv (the variation of the
 * master normal and the sliding of the foot), and
 *     d da / d x_a = w J N1_a,alpha tau^alpha
 * when the area element follows the deformation (finite_def). */
static int link_geometry(const ffc_effects *fx, int ns, const double Xs[][3], const double Xs0[][3],
                         const double xs[2], double w, int nm, const double Xm[][3],
                         ffc_link_state *st, lgeo_t *g, double D[FFC_MAXDOF][FFC_MAXDOF])
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
    ffc_proj pr;
    s = ffc__project_free(nm, Xm, p, &pr);
    if (s) return s;
    memset(st, 0, sizeof *st);
    for (int i = 0; i < 3; i++) { st->x[i] = p[i]; st->n[i] = pr.n[i]; }
    st->xi[0] = pr.xi[0];
    st->xi[1] = pr.xi[1];
    st->gap = pr.gap;
    st->da = w * sp.j;
    s = ffc_project_deriv(ns, g->N1, nm, Xm, &pr, g->dxi, g->G, g->dn);
    if (s) return s;
    ffc_shape(nm, pr.xi, g->N2, g->dN2);
    for (int k = 0; k < nd; k++) g->dda[k] = 0.0;
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
    if (!D) return FFC_OK;
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

/* ------------------------------------------------------------- friction */
int ffc_friction_map(const double n[3], const double lam_t[3], const double r[3],
                     double mu, double eps_t, double tn, ffc_fric *out)
{
    if (!n || !lam_t || !r || !out) return FFC_ERR_NULL;
    if (!(mu >= 0) || isinf(mu) || !(eps_t > 0) || isinf(eps_t)) return FFC_ERR_VALUE;
    for (int i = 0; i < 3; i++)
        if (!isfinite(n[i]) || !isfinite(lam_t[i]) || !isfinite(r[i])) return FFC_ERR_NONFINITE;
    if (isnan(tn)) return FFC_ERR_NONFINITE;
    memset(out, 0, sizeof *out);
    out->state = FFC_FRIC_OPEN;
    if (!(tn > 0.0)) return FFC_OK;
    /* v = lambda_T + eps_T r, T_tr = P v,
     * dT_tr/dr = eps_T P,  dT_tr/dn = -(n.v) I - n v^T */
    double v[3], ttr[3], A[3][3], B[3][3];
    for (int i = 0; i < 3; i++) v[i] = lam_t[i] + eps_t * r[i];
    const double nv = ffc__dot(n, v);
    for (int i = 0; i < 3; i++) ttr[i] = v[i] - n[i] * nv;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            A[i][j] = eps_t * ((i == j) - n[i] * n[j]);
            B[i][j] = -nv * (i == j) - n[i] * v[j];
        }
    const double norm = sqrt(ffc__dot(ttr, ttr)), bound = mu * tn;
    if (norm < bound) {
        out->state = FFC_FRIC_STICK;
        for (int i = 0; i < 3; i++) {
            out->t[i] = ttr[i];
            for (int j = 0; j < 3; j++) { out->dt_dr[i][j] = A[i][j]; out->dt_dn[i][j] = B[i][j]; }
        }
        return FFC_OK;
    }
    out->state = FFC_FRIC_SLIP;
    if (!(norm > 0.0)) return FFC_OK; /* mu t_N = 0 and no trial traction: T = 0 */
    /* T = mu t_N e, e = T_tr / |T_tr|:
     * dT = mu e dt_N + (mu t_N / |T_tr|) (I - e e^T) dT_tr */
    double e[3], M[3][3];
    for (int i = 0; i < 3; i++) e[i] = ttr[i] / norm;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) M[i][j] = bound / norm * ((i == j) - e[i] * e[j]);
    for (int i = 0; i < 3; i++) {
        out->t[i] = bound * e[i];
        out->dt_dtn[i] = mu * e[i];
        for (int j = 0; j < 3; j++) {
            double a = 0, b = 0;
            for (int k = 0; k < 3; k++) { a += M[i][k] * A[k][j]; b += M[i][k] * B[k][j]; }
            out->dt_dr[i][j] = a;
            out->dt_dn[i][j] = b;
        }
    }
    return FFC_OK;
}

/* slip r = sum_a N1_a Ds_a - sum_b N2_b(xi) Dm_b, with the nodal motion D
 * = x - x^n (quasi-static) or the velocity v (dynamic) */
static void link_slip(const lgeo_t *g, const double Ds[][3], const double Dm[][3], double r[3])
{
    for (int i = 0; i < 3; i++) {
        double v = 0.0;
        for (int a = 0; a < g->ns; a++) v += g->N1[a] * Ds[a][i];
        for (int b = 0; b < g->nm; b++) v -= g->N2[b] * Dm[b][i];
        r[i] = v;
    }
}

/* Q = dr/du (3 x nd) = c S - sum_b Dm_b (N2_b,alpha dxi_alpha/du)^T, with
 * S (3 x nd) = [N1_a I ; -N2_b(xi) I] = dr/dD at fixed foot and c = dD/du
 * (1 quasi-static; the integrator's dv/du dynamic, where c S is the
 * damping part); sw[k] the weight of S in row k % 3 of column k.
 * material_only: Q = c S. */
static void link_slip_deriv(const lgeo_t *g, const double Dm[][3], double c, int material_only,
                            double sw[FFC_MAXDOF], double Q[3][FFC_MAXDOF])
{
    const int ns = g->ns, nd = g->nd;
    for (int k = 0; k < nd; k++) sw[k] = k < 3 * ns ? g->N1[k / 3] : -g->N2[(k - 3 * ns) / 3];
    for (int l = 0; l < nd; l++) {
        for (int j = 0; j < 3; j++) Q[j][l] = (l % 3 == j) ? c * sw[l] : 0.0;
        if (material_only) continue;
        for (int b = 0; b < g->nm; b++) {
            const double dx = g->dN2[b][0] * g->dxi[0][l] + g->dN2[b][1] * g->dxi[1][l];
            for (int j = 0; j < 3; j++) Q[j][l] -= Dm[b][j] * dx;
        }
    }
}

/* dD/du of the friction motion (1, or law->dvdu in the velocity form) and
 * the factor from the map's r to the slip over the step (1, or law->dt) */
static double motion_coef(const ffc_effects *fx, const ffc_law *law)
{
    return fx->dynamic ? law->dvdu : 1.0;
}
static double slip_scale(const ffc_effects *fx, const ffc_law *law)
{
    return fx->dynamic ? law->dt : 1.0;
}

/* Formulation (friction at one link, traction T held fixed).  Residual
 * R_f = da S^T T, i.e. R_f[k] = da sw[k] T[k % 3]: the friction force acts
 * at the current foot, with S as in link_slip_deriv.  Its derivative at
 * fixed T, added into K here:
 *     - da [master b] T (N2_b,alpha dxi_alpha/du)^T   (foot sliding in S)
 *     + S^T T dda^T                                    (area)
 * (callers skip it with material_only). */
static void link_friction_geo(const lgeo_t *g, double da, const double sw[FFC_MAXDOF], const double T[3],
                              double K[FFC_MAXDOF][FFC_MAXDOF])
{
    const int ns = g->ns, nd = g->nd;
    for (int k = 3 * ns; k < nd; k++) {
        const int b = (k - 3 * ns) / 3;
        for (int l = 0; l < nd; l++)
            K[k][l] -= da * T[k % 3] * (g->dN2[b][0] * g->dxi[0][l] + g->dN2[b][1] * g->dxi[1][l]);
    }
    for (int k = 0; k < nd; k++)
        for (int l = 0; l < nd; l++) K[k][l] += sw[k] * T[k % 3] * g->dda[l];
}

/* Formulation (pointwise friction at one link).  T = T(n, lambda_T, r,
 * t_N) by the return map, so with the slip's exact derivative Q:
 *     dT/du = dT/dr Q + dT/dn dn/du + dT/dt_N (dt_N/du)^T,
 *     K_f = da S^T (dT/dr Q + dT/dn dn/du) + (link_friction_geo)
 *         + F (dt_N/du)^T,   F = da S^T dT/dt_N  (returned; the caller
 * knows dt_N/du = -eps_N G).  material_only keeps da S^T dT/dr c S and F.
 * Dynamic: Q = c S + (foot sliding at fixed velocities), so the c-part
 * da S^T dT/dr S is the damping matrix D (times c = dv/du). */
static void link_friction(const lgeo_t *g, const ffc_link_state *st, const double Dm[][3], double c,
                          const ffc_fric *f, int material_only,
                          double R[FFC_MAXDOF], double K[FFC_MAXDOF][FFC_MAXDOF], double F[FFC_MAXDOF])
{
    const int nd = g->nd;
    const double da = st->da;
    double sw[FFC_MAXDOF], Q[3][FFC_MAXDOF];
    link_slip_deriv(g, Dm, c, material_only, sw, Q);
    for (int k = 0; k < nd; k++) {
        R[k] += da * sw[k] * f->t[k % 3];
        F[k] = da * sw[k] * f->dt_dtn[k % 3];
    }
    if (!K) return;
    if (!material_only) link_friction_geo(g, da, sw, f->t, K);
    double dT[3][FFC_MAXDOF];
    for (int l = 0; l < nd; l++)
        for (int i = 0; i < 3; i++) {
            double v = 0.0;
            for (int j = 0; j < 3; j++) {
                v += f->dt_dr[i][j] * Q[j][l];
                if (!material_only) v += f->dt_dn[i][j] * g->dn[j][l];
            }
            dT[i][l] = v;
        }
    for (int k = 0; k < nd; k++)
        for (int l = 0; l < nd; l++) K[k][l] += da * sw[k] * dT[k % 3][l];
}

static int friction_on(const ffc_effects *fx, const ffc_law *law)
{
    return fx->friction && law->mu > 0.0;
}

/* the velocity form's time step and dv/du: dt > 0, dvdu >= 0, finite */
static int dynamic_ok(const ffc_law *law)
{
    return law->dt > 0 && isfinite(law->dt) && law->dvdu >= 0 && isfinite(law->dvdu);
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
 * with G, D, dda from link_geometry.  With friction, link_friction adds
 * its terms and the coupling F (dt_N/du)^T = -eps F G^T. */
int ffc_link_contact(const ffc_effects *effects, int ns, const double Xs[][3],
                     const double Xs0[][3], const double Ds[][3], const double xs[2],
                     double w, int nm, const double Xm[][3], const double Dm[][3],
                     double lambda, const double lam_t[3], const ffc_law *law,
                     ffc_link_state *st, double R[FFC_MAXDOF],
                     double K[FFC_MAXDOF][FFC_MAXDOF])
{
    if (!effects || !Xs || !Xs0 || !xs || !Xm || !st || !R || !law) return FFC_ERR_NULL;
    if ((ns != 3 && ns != 6) || (nm != 3 && nm != 6)) return FFC_ERR_NODES;
    const double eps = law->eps_n;
    if (!(eps > 0) || isinf(eps) || !isfinite(lambda) || !(w > 0)) return FFC_ERR_VALUE;
    const int fric = friction_on(effects, law);
    if (fric && (!Ds || !Dm || !lam_t)) return FFC_ERR_NULL;
    if (fric && effects->dynamic && !dynamic_ok(law)) return FFC_ERR_VALUE;
    const int nd = 3 * (ns + nm);
    for (int k = 0; k < nd; k++) R[k] = 0.0;
    if (K)
        for (int k = 0; k < nd; k++) memset(K[k], 0, (size_t)nd * sizeof K[k][0]);
    lgeo_t g;
    int s = link_geometry(effects, ns, Xs, Xs0, xs, w, nm, Xm, st, &g, K && !law->material_only ? K : NULL);
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
                K[k][l] = law->material_only ? da * eps * g.G[k] * g.G[l]
                                             : da * (eps * g.G[k] * g.G[l] - tn * K[k][l]) - tn * g.G[k] * g.dda[l];
    }
    if (!fric) return FFC_OK;
    double r[3];
    link_slip(&g, Ds, Dm, r);
    ffc_fric f;
    s = ffc_friction_map(st->n, lam_t, r, law->mu, law->eps_t, tn, &f);
    if (s) return s;
    const double sc = slip_scale(effects, law);
    for (int i = 0; i < 3; i++) { st->t[i] = f.t[i]; st->slip[i] = sc * r[i]; }
    st->fstate = f.state;
    double F[FFC_MAXDOF];
    link_friction(&g, st, Dm, motion_coef(effects, law), &f, law->material_only, R, K, F);
    if (K)
        for (int k = 0; k < nd; k++)
            for (int l = 0; l < nd; l++) K[k][l] -= eps * F[k] * g.G[l];
    return FFC_OK;
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
    ffc_law law = {eps, 0, 0, 0.0, 0.0, 0.0, 0.0};
    return ffc_link_contact(&fx, ns, Xs, Xs0, NULL, xs, w, nm, Xm, NULL, lambda, NULL, &law, st, R, K);
}

/* ------------------------------------------------------- over all links */
static int check_pair(const ffc_pair *P)
{
    if (!P || !P->Fs || !P->Fm || !P->X || !P->u) return FFC_ERR_NULL;
    if ((P->ns != 3 && P->ns != 6) || (P->nm != 3 && P->nm != 6)) return FFC_ERR_NODES;
    if (P->nfs <= 0 || P->nfm <= 0) return FFC_ERR_EMPTY;
    if (P->nv <= 0) return FFC_ERR_SIZE;
    return FFC_OK;
}

/* nodes of facet f: current P, reference P0, dofs, and the friction
 * motion D: u - u_prev (quasi-static, mo = u_prev), the velocity (dynamic,
 * mo = v) or zero (mo = NULL) */
static void gather(int nn, const long *F, long f, const double X[], const double u[], const double mo[],
                   int velocity, double P[][3], double P0[][3], double D[][3], long dof[])
{
    for (int a = 0; a < nn; a++) {
        long v = F[f * nn + a];
        for (int i = 0; i < 3; i++) {
            P0[a][i] = X[3 * v + i];
            P[a][i] = X[3 * v + i] + u[3 * v + i];
            D[a][i] = !mo ? 0.0 : velocity ? mo[3 * v + i] : u[3 * v + i] - mo[3 * v + i];
            dof[3 * a + i] = 3 * v + i;
        }
    }
}

/* The facets of one link, gathered. */
typedef struct {
    double Xs[FFC_MAXNODES][3], Xs0[FFC_MAXNODES][3], Ds[FFC_MAXNODES][3];
    double Xm[FFC_MAXNODES][3], Xm0[FFC_MAXNODES][3], Dm[FFC_MAXNODES][3];
    long dof[FFC_MAXDOF];
    int nd;
} lnodes_t;

static int gather_link(const ffc_effects *fx, const ffc_pair *P, int nq, const ffc_link *lk, lnodes_t *n)
{
    if (lk->sf < 0 || lk->sf >= P->nfs || lk->q < 0 || lk->q >= nq || lk->mf >= P->nfm) return FFC_ERR_INDEX;
    for (int a = 0; a < P->ns; a++)
        if (P->Fs[lk->sf * P->ns + a] < 0 || P->Fs[lk->sf * P->ns + a] >= P->nv) return FFC_ERR_INDEX;
    for (int a = 0; a < P->nm; a++)
        if (P->Fm[lk->mf * P->nm + a] < 0 || P->Fm[lk->mf * P->nm + a] >= P->nv) return FFC_ERR_INDEX;
    const double *mo = fx->dynamic ? P->v : P->u_prev;
    gather(P->ns, P->Fs, lk->sf, P->X, P->u, mo, fx->dynamic, n->Xs, n->Xs0, n->Ds, n->dof);
    gather(P->nm, P->Fm, lk->mf, P->X, P->u, mo, fx->dynamic, n->Xm, n->Xm0, n->Dm, n->dof + 3 * P->ns);
    n->nd = 3 * (P->ns + P->nm);
    return FFC_OK;
}

#define CP3(a) ((const double(*)[3])(a))

/* Evaluates link k (pointwise law): state, residual (and tangent when
 * K != NULL), and the global dofs of its unknowns; *nd their count. */
static int eval_link(const ffc_effects *fx, const ffc_pair *P, const double qw[], int nq,
                     const ffc_link *lk, double lambda, const double lam_t[3], const ffc_law *law,
                     ffc_link_state *st, double R[FFC_MAXDOF], double K[FFC_MAXDOF][FFC_MAXDOF],
                     long dof[FFC_MAXDOF], int *nd)
{
    lnodes_t n;
    int s = gather_link(fx, P, nq, lk, &n);
    if (s) return s;
    memcpy(dof, n.dof, sizeof n.dof);
    *nd = n.nd;
    return ffc_link_contact(fx, P->ns, CP3(n.Xs), CP3(n.Xs0), CP3(n.Ds), lk->xs, qw[lk->q], P->nm, CP3(n.Xm),
                            CP3(n.Dm), lambda, lam_t, law, st, R, K);
}

static void stats_init(ffc_stats *s)
{
    memset(s, 0, sizeof *s);
}

/* a point pressed by t > 0 over the area da, normal n */
static void stats_pressure(ffc_stats *s, double t, double da, const double n[3])
{
    s->active++;
    if (t > s->max_tn) s->max_tn = t;
    for (int i = 0; i < 3; i++) s->force[i] += t * da * n[i];
}

/* |r - (r . n) n|: the tangential part of r for a unit n */
static double tangential_norm(const double r[3], const double n[3])
{
    const double rn = ffc__dot(r, n), rt[3] = {r[0] - rn * n[0], r[1] - rn * n[1], r[2] - rn * n[2]};
    return sqrt(ffc__dot(rt, rt));
}

/* an active point (pointwise law): pressure t, and its friction state */
static void stats_active(ffc_stats *s, double t, const ffc_link_state *st, int fric)
{
    stats_pressure(s, t, st->da, st->n);
    if (!fric) return;
    s->stick += st->fstate == FFC_FRIC_STICK;
    s->slip += st->fstate == FFC_FRIC_SLIP;
    const double tt = sqrt(ffc__dot(st->t, st->t));
    if (tt > s->max_tt) s->max_tt = tt;
    for (int i = 0; i < 3; i++) s->force_t[i] -= st->t[i] * st->da;
    s->dissipation += st->da * ffc__dot(st->t, st->slip);
    const double rt = tangential_norm(st->slip, st->n);
    if (rt > s->max_slip) s->max_slip = rt;
}

static void stats_add(ffc_stats *s, const ffc_link_state *st, int fric)
{
    s->linked++;
    if (-st->gap > s->max_pen) s->max_pen = -st->gap;
    if (st->active) stats_active(s, st->tn, st, fric);
}

/* The checks every call over all links shares: pair, law, quadrature rule
 * (its weights into qw, point count *nq), link count, slave node indices,
 * finite multipliers (lambda[nv] and lam_t[3 nv] nodal, lambda[nl] and
 * lam_t[3 nl] per link, lam_t with friction only; *bad = the index of a
 * non-finite one) and, with friction,
 * finite previous displacements. */
static int common_checks(const ffc_effects *fx, const ffc_pair *P, int qdeg, long nl,
                         const ffc_link links[], const ffc_law *law, const double lambda[],
                         const double lam_t[], double qw[16], int *nq, long *bad)
{
    if (!fx || !links || !law || !lambda) return FFC_ERR_NULL;
    int s = check_pair(P);
    if (s) return s;
    if (!(law->eps_n > 0) || isinf(law->eps_n) || (law->nodal != 0 && law->nodal != 1) ||
        (law->material_only != 0 && law->material_only != 1))
        return FFC_ERR_VALUE;
    if (fx->friction && (!(law->mu >= 0) || isinf(law->mu))) return FFC_ERR_VALUE;
    const int fric = friction_on(fx, law);
    if (fric && (!(law->eps_t > 0) || isinf(law->eps_t))) return FFC_ERR_VALUE;
    if (fric && fx->dynamic && !dynamic_ok(law)) return FFC_ERR_VALUE;
    const double *mo = fx->dynamic ? P->v : P->u_prev;
    if (fric && (!lam_t || !mo)) return FFC_ERR_NULL;
    double qxi[16][2];
    *nq = ffc_quad(qdeg, 16, qxi, qw);
    if (*nq < 0) return *nq;
    if (nl != P->nfs * *nq) return FFC_ERR_SIZE;
    for (long k = 0; k < P->nfs * P->ns; k++)
        if (P->Fs[k] < 0 || P->Fs[k] >= P->nv) return FFC_ERR_INDEX;
    const long n = law->nodal ? P->nv : nl;
    for (long k = 0; k < n; k++)
        if (!isfinite(lambda[k])) { *bad = k; return FFC_ERR_NONFINITE; }
    if (fric) {
        for (long k = 0; k < 3 * n; k++)
            if (!isfinite(lam_t[k])) { *bad = k / 3; return FFC_ERR_NONFINITE; }
        for (long k = 0; k < 3 * P->nv; k++)
            if (!isfinite(mo[k])) return FFC_ERR_NONFINITE;
    }
    return FFC_OK;
}

/* ----------------------------------------------- nodal (mortar-type) law */
/* Formulation (nodal multipliers).  For slave node a, over the linked
 * points q of its facets:
 *     G_a = sum_q N_a(q) da_q g_q,   W_a = sum_q N_a(q) da_q,
 *     g~_a = G_a / W_a (weighted gap),   t_a = <lambda_a - eps g~_a>.
 * The pressure at a point is t_q = sum_a N_a(q) t_a and the virtual work
 * sum_q t_q da_q dg_q gives the residual
 *     R = -sum_q t_q da_q G_q.
 * Its derivative:
 *     K = -sum_q t_q (da_q D_q + G_q dda_q^T)               (geometric)
 *       + sum_a (eps H(t_a) / W_a) B_a C_a^T                 (material)
 * with H(t_a) = 1 when lambda_a - eps g~_a >= 0 (touching counts, to round-off: >= -eps 1e-12 sqrt(W_a)).
 *     B_a = sum_q N_a(q) da_q G_q,
 *     C_a = sum_q N_a(q) (da_q G_q + (g_q - g~_a) dda_q)   (= dG_a - g~_a dW_a).
 * The Uzawa update lambda_a <- t_a has the fixed point g~_a = 0 where
 * t_a > 0 and g~_a >= 0, lambda_a = 0 elsewhere: one constraint per slave
 * node, the weighted-gap conditions of mortar methods.
 *
 * Friction, the same way: per node the weighted slip and normal
 *     r~_a = sum_q N_a da_q r_q / W_a,   m_a = sum_q N_a da_q n_q,  n~_a = m_a / |m_a|,
 * the return map at the node T_a = T(n~_a, lambda_T,a, r~_a, t_a), and the
 * point traction T_q = sum_a N_a(q) T_a.  Residual R_f = sum_q da_q S_q^T T_q.
 * Derivative: the link terms at fixed T_q (link_friction_geo) plus
 *     sum_a Bf_a dT_a,   Bf_a = sum_q N_a da_q S_q^T  (nd x 3),
 *     dT_a = dT/dr dr~_a + dT/dn dn~_a - dT/dt_N (eps H(t_a) / W_a) C_a^T,
 *     dr~_a = [sum_q N_a (da_q Q_q + (r_q - r~_a) dda_q^T)] / W_a,
 *     dn~_a = (I - n~ n~^T) / |m_a| sum_q N_a (da_q dn_q + n_q dda_q^T).
 * The Uzawa update lambda_T,a <- T_a drives the weighted slip of sticking
 * nodes to zero: one tangential constraint (a 2-vector) per node, as many
 * as there are tangential unknowns (pointwise multipliers would impose
 * more and drift). */
typedef struct {
    long k;                 /* link index */
    int nd;                 /* unknowns */
    double g, da;           /* gap, point area */
    double n[3];            /* master normal at the foot */
    double N[FFC_MAXNODES]; /* slave (multiplier) shape values at the point */
    long dof[FFC_MAXDOF];
    double G[FFC_MAXDOF], dda[FFC_MAXDOF];
} nlink_t;

/* friction data of a linked point (nodal law with friction) */
typedef struct {
    double r[3];                /* slip since the last converged step, or relative velocity (dynamic) */
    double sw[FFC_MAXDOF];      /* weights of S */
    double Q[3][FFC_MAXDOF];    /* dr/du */
    double dn[3][FFC_MAXDOF];   /* dn/du */
} nfl_t;

/* return map at a node */
typedef struct {
    double r[3], n[3], mnorm;   /* weighted slip (or relative velocity), normal n~, |m| */
    ffc_fric f;                 /* traction T_a and its derivatives */
} nfn_t;

typedef struct {
    long n;          /* linked links */
    nlink_t *L;      /* [n] */
    double *Gn, *Wn; /* [nv] weighted gap sums and weights per node */
    double *tn;      /* [nv] nodal pressures */
    unsigned char *on; /* [nv] 1 when lambda_a - eps g~_a >= 0: the node touches
                          and its stiffness enters the tangent (a node at
                          exactly zero gap and zero multiplier included, so
                          that a body held only by contact is not singular
                          at the first iteration) */
    nfl_t *F;        /* [n] friction data per linked point (NULL without friction) */
    nfn_t *T;        /* [nv] friction at the nodes (NULL without friction) */
} nodal_t;

static void nodal_free(nodal_t *w)
{
    free(w->L);
    free(w->Gn);
    free(w->Wn);
    free(w->tn);
    free(w->on);
    free(w->F);
    free(w->T);
}

/* pass 1: geometry of every linked point, nodal sums and pressures; with
 * friction (lam_t != NULL) the slips and the nodal return maps */
/* Formulation (a touching node).  A node whose trial pressure is exactly
 * zero (the gap closed, no load yet: w->on, t_N = 0) and whose trial
 * traction T_tr = P (lambda_T + eps_T r) vanishes sits on the kink of the
 * return map, where the stick branch (T = T_tr, dT/dr = eps_T P,
 * dT/dn = -(n.v) I - n v^T with v = lambda_T + eps_T r) and the slip branch
 * (T = mu t_N e = 0, derivative 0) meet.  Both give T = 0; the stick
 * branch's derivative is taken (an element of the generalized Jacobian,
 * as in a semi-smooth Newton method), so that a body held only by
 * frictional contact (a block between two others) has a regular first
 * system; with the slip branch's it would be free to translate. */
static void touching_stick(nfn_t *T, const double lam_t[3], double eps_t)
{
    double v[3], ttr[3];
    for (int i = 0; i < 3; i++) v[i] = lam_t[i] + eps_t * T->r[i];
    const double nv = ffc__dot(T->n, v);
    for (int i = 0; i < 3; i++) ttr[i] = v[i] - T->n[i] * nv;
    if (T->f.state != FFC_FRIC_OPEN || ffc__dot(ttr, ttr) != 0.0) return;
    T->f.state = FFC_FRIC_STICK;
    for (int i = 0; i < 3; i++) {
        T->f.t[i] = 0.0;
        T->f.dt_dtn[i] = 0.0;
        for (int j = 0; j < 3; j++) {
            T->f.dt_dr[i][j] = eps_t * ((i == j) - T->n[i] * T->n[j]);
            T->f.dt_dn[i][j] = -nv * (i == j) - T->n[i] * v[j];
        }
    }
}

static int nodal_prepare(const ffc_effects *fx, const ffc_pair *P, const double qw[], int nq, long nl,
                         const ffc_link links[], const double lambda[], const double lam_t[], const ffc_law *law,
                         nodal_t *w, ffc_stats *stats, long *bad)
{
    const double eps = law->eps_n;
    memset(w, 0, sizeof *w);
    long n = 0;
    for (long k = 0; k < nl; k++) n += links[k].mf >= 0;
    w->L = malloc((size_t)(n > 0 ? n : 1) * sizeof *w->L);
    w->Gn = calloc((size_t)P->nv, sizeof *w->Gn);
    w->Wn = calloc((size_t)P->nv, sizeof *w->Wn);
    w->tn = calloc((size_t)P->nv, sizeof *w->tn);
    w->on = calloc((size_t)P->nv, 1);
    if (lam_t) {
        w->F = malloc((size_t)(n > 0 ? n : 1) * sizeof *w->F);
        w->T = calloc((size_t)P->nv, sizeof *w->T);
    }
    if (!w->L || !w->Gn || !w->Wn || !w->tn || !w->on || (lam_t && (!w->F || !w->T))) {
        nodal_free(w);
        return FFC_ERR_MEMORY;
    }
    for (long k = 0; k < nl; k++) {
        const ffc_link *lk = &links[k];
        if (lk->mf < 0) continue;
        nlink_t *e = &w->L[w->n];
        lnodes_t ln;
        int s = gather_link(fx, P, nq, lk, &ln);
        if (s) { *bad = k; nodal_free(w); return s; }
        memcpy(e->dof, ln.dof, sizeof ln.dof);
        e->k = k;
        e->nd = ln.nd;
        ffc_link_state st;
        lgeo_t g;
        s = link_geometry(fx, P->ns, CP3(ln.Xs), CP3(ln.Xs0), lk->xs, qw[lk->q], P->nm, CP3(ln.Xm), &st, &g, NULL);
        if (s) { *bad = k; nodal_free(w); return s; }
        memcpy(e->G, g.G, sizeof e->G);
        memcpy(e->dda, g.dda, sizeof e->dda);
        e->g = st.gap;
        e->da = st.da;
        for (int i = 0; i < 3; i++) e->n[i] = st.n[i];
        /* multipliers are linear on the facet's vertices (for 6-node facets
         * too: quadratic vertex shape functions integrate to zero, which
         * would leave vertex nodes without weight) */
        ffc_shape(3, lk->xs, e->N, NULL);
        for (int a = 3; a < P->ns; a++) e->N[a] = 0.0;
        if (lam_t) {
            nfl_t *fl = &w->F[w->n];
            link_slip(&g, CP3(ln.Ds), CP3(ln.Dm), fl->r);
            link_slip_deriv(&g, CP3(ln.Dm), motion_coef(fx, law), law->material_only, fl->sw, fl->Q);
            memcpy(fl->dn, g.dn, sizeof fl->dn);
        }
        for (int a = 0; a < P->ns; a++) {
            long v = P->Fs[lk->sf * P->ns + a];
            w->Gn[v] += e->N[a] * e->da * e->g;
            w->Wn[v] += e->N[a] * e->da;
            if (lam_t)
                for (int i = 0; i < 3; i++) {
                    w->T[v].r[i] += e->N[a] * e->da * w->F[w->n].r[i];
                    w->T[v].n[i] += e->N[a] * e->da * e->n[i];
                }
        }
        if (stats) {
            stats->linked++;
            if (-e->g > stats->max_pen) stats->max_pen = -e->g;
        }
        w->n++;
    }
    for (long v = 0; v < P->nv; v++)
        if (w->Wn[v] > 0.0) {
            double g = w->Gn[v] / w->Wn[v];
            const double trial = lambda[v] - eps * g;
            w->tn[v] = fmax(0.0, trial);
            /* touching: the gap closed to round-off (two bodies meshed on one
             * plane carry gaps of +-1e-17) counts as on the kink */
            w->on[v] = trial >= -eps * 1e-12 * sqrt(w->Wn[v]);
            if (stats && w->tn[v] > 0.0 && -g > stats->max_pen_node) stats->max_pen_node = -g;
            if (!lam_t) continue;
            nfn_t *T = &w->T[v];
            T->mnorm = sqrt(ffc__dot(T->n, T->n));
            for (int i = 0; i < 3; i++) {
                T->r[i] /= w->Wn[v];
                T->n[i] = T->mnorm > 0.0 ? T->n[i] / T->mnorm : 0.0;
            }
            if (!(T->mnorm > 0.0)) continue; /* opposite normals cancel: no friction */
            int s = ffc_friction_map(T->n, lam_t + 3 * v, T->r, law->mu, law->eps_t, w->tn[v], &T->f);
            if (s) { nodal_free(w); return s; }
            if (w->on[v] && !(w->tn[v] > 0.0)) touching_stick(T, lam_t + 3 * v, law->eps_t);
            if (stats && T->f.state != FFC_FRIC_OPEN) {
                stats->stick += T->f.state == FFC_FRIC_STICK;
                stats->slip += T->f.state == FFC_FRIC_SLIP;
                const double tt = sqrt(ffc__dot(T->f.t, T->f.t));
                if (tt > stats->max_tt) stats->max_tt = tt;
                stats->dissipation += slip_scale(fx, law) * w->Wn[v] * ffc__dot(T->f.t, T->r);
                const double rt = slip_scale(fx, law) * tangential_norm(T->r, T->n);
                if (rt > stats->max_slip) stats->max_slip = rt;
            }
        }
    return FFC_OK;
}

/* pressure at a linked point: the interpolated nodal pressure */
static double nodal_point_pressure(const ffc_pair *P, const ffc_link *lk, const nlink_t *e, const double tn[])
{
    double t = 0.0;
    for (int a = 0; a < P->ns; a++) t += e->N[a] * tn[P->Fs[lk->sf * P->ns + a]];
    return t;
}

/* traction at a linked point: the interpolated nodal tractions; *state the
 * "largest" state of its nodes (slip > stick > open) */
static void nodal_point_traction(const ffc_pair *P, const ffc_link *lk, const nlink_t *e, const nfn_t T[],
                                 double t[3], int *state)
{
    t[0] = t[1] = t[2] = 0.0;
    *state = FFC_FRIC_OPEN;
    for (int a = 0; a < P->ns; a++) {
        if (e->N[a] == 0.0) continue;
        const nfn_t *Ta = &T[P->Fs[lk->sf * P->ns + a]];
        for (int i = 0; i < 3; i++) t[i] += e->N[a] * Ta->f.t[i];
        if (Ta->f.state > *state) *state = Ta->f.state;
    }
}

/* statistics of a linked point of the nodal law: pressure t (counted when
 * > 0) and friction traction Tq */
static void nodal_point_stats(ffc_stats *s, double t, const nlink_t *e, const double Tq[3])
{
    if (t > 0.0) stats_pressure(s, t, e->da, e->n);
    for (int i = 0; i < 3; i++) s->force_t[i] -= Tq[i] * e->da;
}

static int emit(long *nt, long cap, long Ti[], long Tj[], double Tv[], long i, long j, double v)
{
    if (*nt < cap) { Ti[*nt] = i; Tj[*nt] = j; Tv[*nt] = v; }
    (*nt)++;
    return *nt <= cap;
}

/* per-node work arrays of the material stiffness */
typedef struct {
    long *start, *lst, *pos, *loc;
    double *Bv, *Cv;            /* [maxloc] */
    double *Bf, *Rt, *Nt;       /* [3 maxloc] friction: Bf_a, dr~_a, dn~_a */
} nodework_t;

static void nodework_free(nodework_t *k)
{
    free(k->start); free(k->lst); free(k->pos); free(k->loc);
    free(k->Bv); free(k->Cv); free(k->Bf); free(k->Rt); free(k->Nt);
}

static int nodework_alloc(const ffc_pair *P, const ffc_link links[], const nodal_t *w, nodework_t *k)
{
    memset(k, 0, sizeof *k);
    const long nv = P->nv;
    k->start = calloc((size_t)nv + 1, sizeof *k->start);
    if (!k->start) return FFC_ERR_MEMORY;
    for (long e = 0; e < w->n; e++)
        for (int a = 0; a < P->ns; a++) k->start[P->Fs[links[w->L[e].k].sf * P->ns + a] + 1]++;
    for (long v = 0; v < nv; v++) k->start[v + 1] += k->start[v];
    k->lst = malloc((size_t)(k->start[nv] > 0 ? k->start[nv] : 1) * sizeof *k->lst);
    k->pos = malloc((size_t)3 * nv * sizeof *k->pos);
    long *fill = calloc((size_t)nv, sizeof *fill);
    long maxloc = 1;
    for (long v = 0; v < nv; v++)
        if (FFC_MAXDOF * (k->start[v + 1] - k->start[v]) > maxloc) maxloc = FFC_MAXDOF * (k->start[v + 1] - k->start[v]);
    k->loc = malloc((size_t)maxloc * sizeof *k->loc);
    k->Bv = malloc((size_t)maxloc * sizeof *k->Bv);
    k->Cv = malloc((size_t)maxloc * sizeof *k->Cv);
    if (w->T) {
        k->Bf = malloc((size_t)3 * maxloc * sizeof *k->Bf);
        k->Rt = malloc((size_t)3 * maxloc * sizeof *k->Rt);
        k->Nt = malloc((size_t)3 * maxloc * sizeof *k->Nt);
    }
    if (!k->lst || !k->pos || !fill || !k->loc || !k->Bv || !k->Cv || (w->T && (!k->Bf || !k->Rt || !k->Nt))) {
        free(fill);
        nodework_free(k);
        return FFC_ERR_MEMORY;
    }
    for (long e = 0; e < w->n; e++)
        for (int a = 0; a < P->ns; a++) {
            long v = P->Fs[links[w->L[e].k].sf * P->ns + a];
            k->lst[k->start[v] + fill[v]++] = e;
        }
    free(fill);
    for (long i = 0; i < 3 * nv; i++) k->pos[i] = -1;
    return FFC_OK;
}

static int assemble_nodal(const ffc_effects *fx, const ffc_pair *P, const double qw[], int nq, long nl,
                          const ffc_link links[], const double lambda[], const double lam_t[],
                          const ffc_law *law, double R[], long cap, long Ti[], long Tj[], double Tv[],
                          long *ntrip, ffc_stats *stats, long *bad)
{
    const double eps = law->eps_n;
    const int material_only = law->material_only, fric = friction_on(fx, law);
    nodal_t w;
    int s = nodal_prepare(fx, P, qw, nq, nl, links, lambda, fric ? lam_t : NULL, law, &w, stats, bad);
    if (s) return s;
    const int want_k = Ti && Tj && Tv;
    long nt = 0;
    int ok = 1;
    double D[FFC_MAXDOF][FFC_MAXDOF];
    /* residual, statistics and geometric stiffness, link by link */
    for (long e = 0; e < w.n; e++) {
        const nlink_t *E = &w.L[e];
        const ffc_link *lk = &links[E->k];
        const double t = nodal_point_pressure(P, lk, E, w.tn);
        double Tq[3] = {0, 0, 0};
        int fs = FFC_FRIC_OPEN;
        if (fric) nodal_point_traction(P, lk, E, w.T, Tq, &fs);
        const int has_t = fric && (Tq[0] != 0.0 || Tq[1] != 0.0 || Tq[2] != 0.0);
        if (!(t > 0.0) && !has_t) continue;
        nodal_point_stats(stats, t, E, Tq);
        for (int a = 0; a < E->nd; a++) R[E->dof[a]] -= t * E->da * E->G[a];
        if (has_t)
            for (int a = 0; a < E->nd; a++) R[E->dof[a]] += E->da * w.F[e].sw[a] * Tq[a % 3];
        if (!want_k || material_only) continue;
        lnodes_t ln;
        s = gather_link(fx, P, nq, lk, &ln);
        ffc_link_state sg;
        lgeo_t g;
        if (!s)
            s = link_geometry(fx, P->ns, CP3(ln.Xs), CP3(ln.Xs0), lk->xs, qw[lk->q], P->nm, CP3(ln.Xm), &sg, &g, D);
        if (s) { *bad = E->k; nodal_free(&w); return s; }
        for (int a = 0; a < E->nd; a++)
            for (int b = 0; b < E->nd; b++) D[a][b] = -t * (E->da * D[a][b] + E->G[a] * E->dda[b]);
        if (has_t) link_friction_geo(&g, E->da, w.F[e].sw, Tq, D);
        for (int a = 0; a < E->nd; a++)
            for (int b = 0; b < E->nd; b++)
                if (D[a][b] != 0.0) ok &= emit(&nt, cap, Ti, Tj, Tv, E->dof[a], E->dof[b], D[a][b]);
    }
    if (want_k) {
        /* material stiffness, node by node: links of each slave node */
        nodework_t k;
        if (nodework_alloc(P, links, &w, &k)) { nodal_free(&w); return FFC_ERR_MEMORY; }
        for (long v = 0; v < P->nv; v++) {
            if (!w.on[v] || !(w.Wn[v] > 0.0)) continue;
            const double W = w.Wn[v], gt = w.Gn[v] / W, c = eps / W;
            const nfn_t *Tn = fric ? &w.T[v] : NULL;
            const int ft = Tn && Tn->f.state != FFC_FRIC_OPEN;
            long nloc = 0;
            for (long m = k.start[v]; m < k.start[v + 1]; m++) {
                const long e = k.lst[m];
                const nlink_t *E = &w.L[e];
                const ffc_link *lk = &links[E->k];
                double Na = 0.0;
                for (int a = 0; a < P->ns; a++)
                    if (P->Fs[lk->sf * P->ns + a] == v) Na += E->N[a];
                for (int a = 0; a < E->nd; a++) {
                    long d = E->dof[a];
                    if (k.pos[d] < 0) {
                        k.pos[d] = nloc; k.loc[nloc] = d; k.Bv[nloc] = k.Cv[nloc] = 0.0;
                        if (ft)
                            for (int i = 0; i < 3; i++) k.Bf[3 * nloc + i] = k.Rt[3 * nloc + i] = k.Nt[3 * nloc + i] = 0.0;
                        nloc++;
                    }
                    const long p = k.pos[d];
                    k.Bv[p] += Na * E->da * E->G[a];
                    k.Cv[p] += Na * (E->da * E->G[a] + (E->g - gt) * E->dda[a]);
                    if (!ft) continue;
                    const nfl_t *fl = &w.F[e];
                    k.Bf[3 * p + a % 3] += Na * E->da * fl->sw[a];
                    for (int i = 0; i < 3; i++) {
                        k.Rt[3 * p + i] += Na * (E->da * fl->Q[i][a] + (fl->r[i] - Tn->r[i]) * E->dda[a]) / W;
                        if (!material_only) k.Nt[3 * p + i] += Na * (E->da * fl->dn[i][a] + E->n[i] * E->dda[a]);
                    }
                }
            }
            for (long i = 0; i < nloc; i++)
                for (long j = 0; j < nloc; j++)
                    if (k.Bv[i] != 0.0 && k.Cv[j] != 0.0) ok &= emit(&nt, cap, Ti, Tj, Tv, k.loc[i], k.loc[j], c * k.Bv[i] * k.Cv[j]);
            if (ft) {
                /* dn~ = (I - n~ n~^T) / |m| (accumulated), then
                 * dT_a = dT/dr dr~ + dT/dn dn~ - dT/dt_N c C^T, K += Bf dT_a */
                const double *nn = Tn->n;
                for (long j = 0; j < nloc; j++) {
                    double *q = &k.Nt[3 * j], d = ffc__dot(nn, q);
                    for (int i = 0; i < 3; i++) q[i] = (q[i] - nn[i] * d) / Tn->mnorm;
                }
                for (long j = 0; j < nloc; j++) {
                    double dT[3];
                    for (int i = 0; i < 3; i++) {
                        double x = -Tn->f.dt_dtn[i] * c * k.Cv[j];
                        for (int l = 0; l < 3; l++)
                            x += Tn->f.dt_dr[i][l] * k.Rt[3 * j + l] + Tn->f.dt_dn[i][l] * k.Nt[3 * j + l];
                        dT[i] = x;
                    }
                    for (long i = 0; i < nloc; i++) {
                        const double x = k.Bf[3 * i] * dT[0] + k.Bf[3 * i + 1] * dT[1] + k.Bf[3 * i + 2] * dT[2];
                        if (x != 0.0) ok &= emit(&nt, cap, Ti, Tj, Tv, k.loc[i], k.loc[j], x);
                    }
                }
            }
            for (long i = 0; i < nloc; i++) k.pos[k.loc[i]] = -1;
        }
        nodework_free(&k);
    }
    *ntrip = nt;
    nodal_free(&w);
    return ok ? FFC_OK : FFC_ERR_CAPACITY;
}

int ffc_assemble(const ffc_effects *effects, const ffc_pair *pair, int qdeg,
                 long nl, const ffc_link links[], const double lambda[],
                 const double lam_t[], const ffc_law *law, double R[], long cap, long Ti[], long Tj[],
                 double Tv[], long *ntrip, ffc_stats *stats, long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    double qw[16];
    int nq;
    int s = common_checks(effects, pair, qdeg, nl, links, law, lambda, lam_t, qw, &nq, bad);
    if (s) return s;
    if (!R || !ntrip) return FFC_ERR_NULL;
    const int want_k = Ti && Tj && Tv, fric = friction_on(effects, law);
    ffc_stats loc;
    if (!stats) stats = &loc;
    stats_init(stats);
    if (law->nodal)
        return assemble_nodal(effects, pair, qw, nq, nl, links, lambda, lam_t, law, R, cap, Ti, Tj, Tv, ntrip,
                              stats, bad);
    long nt = 0;
    int over = 0;
    double Rl[FFC_MAXDOF], Kl[FFC_MAXDOF][FFC_MAXDOF];
    long dof[FFC_MAXDOF];
    for (long k = 0; k < nl; k++) {
        if (links[k].mf < 0) continue;
        ffc_link_state st;
        int nd;
        s = eval_link(effects, pair, qw, nq, &links[k], lambda[k], fric ? lam_t + 3 * k : NULL, law, &st, Rl,
                      want_k ? Kl : NULL, dof, &nd);
        if (s) { *bad = k; return s; }
        stats_add(stats, &st, fric);
        if (!st.active) continue;
        for (int a = 0; a < nd; a++) R[dof[a]] += Rl[a];
        if (!want_k) continue;
        if (nt + (long)nd * nd > cap) { over = 1; nt += (long)nd * nd; continue; }
        for (int a = 0; a < nd; a++)
            for (int b = 0; b < nd; b++) {
                Ti[nt] = dof[a];
                Tj[nt] = dof[b];
                Tv[nt++] = Kl[a][b];
            }
    }
    *ntrip = nt;
    return over ? FFC_ERR_CAPACITY : FFC_OK;
}

int ffc_augment(const ffc_effects *effects, const ffc_pair *pair, int qdeg,
                long nl, const ffc_link links[], double lambda[], double lam_t[],
                const ffc_law *law, ffc_stats *stats, long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    double qw[16];
    int nq;
    int s = common_checks(effects, pair, qdeg, nl, links, law, lambda, lam_t, qw, &nq, bad);
    if (s) return s;
    const int fric = friction_on(effects, law);
    ffc_stats loc;
    if (!stats) stats = &loc;
    stats_init(stats);
    if (law->nodal) {
        /* friction with the pressures of the current multipliers */
        nodal_t w;
        s = nodal_prepare(effects, pair, qw, nq, nl, links, lambda, fric ? lam_t : NULL, law, &w, stats, bad);
        if (s) return s;
        for (long e = 0; e < w.n; e++) {
            const double t = nodal_point_pressure(pair, &links[w.L[e].k], &w.L[e], w.tn);
            if (!(t > 0.0)) continue;
            double Tq[3] = {0, 0, 0};
            int fs;
            if (fric) nodal_point_traction(pair, &links[w.L[e].k], &w.L[e], w.T, Tq, &fs);
            nodal_point_stats(stats, t, &w.L[e], Tq);
        }
        /* the pair's slave nodes only: another pair may keep its multipliers
           in the same array (a node visited twice changes nothing the second time) */
        for (long a = 0; a < pair->nfs * pair->ns; a++) {
            const long v = pair->Fs[a];
            double d = fabs(w.tn[v] - lambda[v]);
            if (d > stats->max_dlam) stats->max_dlam = d;
            lambda[v] = w.tn[v];
            if (!fric) continue;
            for (int i = 0; i < 3; i++) {
                d = fabs(w.T[v].f.t[i] - lam_t[3 * v + i]);
                if (d > stats->max_dlam_t) stats->max_dlam_t = d;
                lam_t[3 * v + i] = w.T[v].f.t[i];
            }
        }
        nodal_free(&w);
        return FFC_OK;
    }
    double Rl[FFC_MAXDOF];
    long dof[FFC_MAXDOF];
    for (long k = 0; k < nl; k++) {
        const ffc_link *lk = &links[k];
        ffc_link_state st;
        memset(&st, 0, sizeof st);
        if (lk->mf >= 0) {
            int nd;
            s = eval_link(effects, pair, qw, nq, lk, lambda[k], fric ? lam_t + 3 * k : NULL, law, &st, Rl, NULL,
                          dof, &nd);
            if (s) { *bad = k; return s; }
            stats_add(stats, &st, fric);
        }
        double d = fabs(st.tn - lambda[k]);
        if (d > stats->max_dlam) stats->max_dlam = d;
        lambda[k] = st.tn;
        if (fric)
            for (int i = 0; i < 3; i++) {
                d = fabs(st.t[i] - lam_t[3 * k + i]);
                if (d > stats->max_dlam_t) stats->max_dlam_t = d;
                lam_t[3 * k + i] = st.t[i];
            }
    }
    stats->max_pen_node = stats->max_pen;
    return FFC_OK;
}

int ffc_points(const ffc_effects *effects, const ffc_pair *pair, int qdeg,
               long nl, const ffc_link links[], const double lambda[],
               const double lam_t[], const ffc_law *law, double P[], long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    double qw[16];
    int nq;
    int s = common_checks(effects, pair, qdeg, nl, links, law, lambda, lam_t, qw, &nq, bad);
    if (s) return s;
    if (!P) return FFC_ERR_NULL;
    const int fric = friction_on(effects, law);
    double Rl[FFC_MAXDOF];
    long dof[FFC_MAXDOF];
    nodal_t w;
    memset(&w, 0, sizeof w);
    if (law->nodal &&
        (s = nodal_prepare(effects, pair, qw, nq, nl, links, lambda, fric ? lam_t : NULL, law, &w, NULL, bad)))
        return s;
    long e = 0;
    for (long k = 0; k < nl; k++) {
        double *row = P + k * FFC_POINT_COLS;
        const ffc_link *lk = &links[k];
        if (lk->sf < 0 || lk->sf >= pair->nfs) { *bad = k; nodal_free(&w); return FFC_ERR_INDEX; }
        ffc_link_state st;
        memset(&st, 0, sizeof st);
        if (lk->mf >= 0) {
            int nd;
            if (law->nodal) { /* geometry, then the interpolated nodal pressure and traction */
                ffc_law l0 = *law;
                l0.mu = 0.0;
                s = eval_link(effects, pair, qw, nq, lk, 0.0, NULL, &l0, &st, Rl, NULL, dof, &nd);
                if (!s) {
                    const nlink_t *E = &w.L[e];
                    st.tn = nodal_point_pressure(pair, lk, E, w.tn);
                    st.active = st.tn > 0.0;
                    if (fric) {
                        nodal_point_traction(pair, lk, E, w.T, st.t, &st.fstate);
                        for (int i = 0; i < 3; i++) st.slip[i] = slip_scale(effects, law) * w.F[e].r[i];
                    }
                    e++;
                }
            } else {
                s = eval_link(effects, pair, qw, nq, lk, lambda[k], fric ? lam_t + 3 * k : NULL, law, &st, Rl,
                              NULL, dof, &nd);
            }
            if (s) { *bad = k; nodal_free(&w); return s; }
        } else {
            /* no partner: the slave point alone */
            double N[FFC_MAXNODES];
            ffc_shape(pair->ns, lk->xs, N, NULL);
            for (int a = 0; a < pair->ns; a++) {
                long v = pair->Fs[lk->sf * pair->ns + a];
                for (int i = 0; i < 3; i++) st.x[i] += N[a] * (pair->X[3 * v + i] + pair->u[3 * v + i]);
            }
            st.gap = NAN;
        }
        row[0] = st.x[0]; row[1] = st.x[1]; row[2] = st.x[2];
        row[3] = st.gap; row[4] = st.tn; row[5] = st.active;
        row[6] = st.da; row[7] = (double)lk->mf;
        row[8] = -st.t[0]; row[9] = -st.t[1]; row[10] = -st.t[2];
        row[11] = st.fstate; row[12] = ffc__dot(st.t, st.slip);
    }
    nodal_free(&w);
    return FFC_OK;
}
