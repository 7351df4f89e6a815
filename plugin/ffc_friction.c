/* ffc_friction.c: Coulomb friction: the return map, the slip of a link and
 * its derivative, the friction residual and tangent of one link. */
#include "ffc.h"
#include "ffc_internal.h"
#include "ffc_link_internal.h"

#include <math.h>
#include <string.h>

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

/* slip r = sum_a N1_a Ds_a - sum_b N2_b(xi) Dm_b - dm (a rigid obstacle's motion), with the nodal motion D
 * = x - x^n (quasi-static) or the velocity v (dynamic) */
void ffc__link_slip(const lgeo_t *g, const double Ds[][3], const double Dm[][3], double r[3])
{
    for (int i = 0; i < 3; i++) {
        double v = 0.0;
        for (int a = 0; a < g->ns; a++) v += g->N1[a] * Ds[a][i];
        for (int b = 0; b < g->nm; b++) v -= g->N2[b] * Dm[b][i];
        r[i] = v - g->dm[i];
    }
}

/* Q = dr/du (3 x nd) = c S - sum_b Dm_b (N2_b,alpha dxi_alpha/du)^T, with
 * S (3 x nd) = [N1_a I ; -N2_b(xi) I] = dr/dD at fixed foot and c = dD/du
 * (1 quasi-static; the integrator's dv/du dynamic, where c S is the
 * damping part); sw[k] the weight of S in row k % 3 of column k.
 * material_only: Q = c S. */
void ffc__link_slip_deriv(const lgeo_t *g, const double Dm[][3], double c, int material_only,
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
double ffc__motion_coef(const ffc_effects *fx, const ffc_law *law)
{
    return fx->dynamic ? law->dvdu : 1.0;
}
double ffc__slip_scale(const ffc_effects *fx, const ffc_law *law)
{
    return fx->dynamic ? law->dt : 1.0;
}

/* Formulation (friction at one link, traction T held fixed).  Residual
 * R_f = da S^T T, i.e. R_f[k] = da sw[k] T[k % 3]: the friction force acts
 * at the current foot, with S as in ffc__link_slip_deriv.  Its derivative
 * at fixed T, added into K here:
 *     - da [master b] T (N2_b,alpha dxi_alpha/du)^T   (foot sliding in S)
 *     + S^T T dda^T                                    (area)
 * (callers skip it with material_only). */
void ffc__link_friction_geo(const lgeo_t *g, double da, const double sw[FFC_MAXDOF], const double T[3],
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
 *     K_f = da S^T (dT/dr Q + dT/dn dn/du) + (ffc__link_friction_geo)
 *         + F (dt_N/du)^T,   F = da S^T dT/dt_N  (returned; the caller
 * knows dt_N/du = -eps_N G).  material_only keeps da S^T dT/dr c S and F.
 * Dynamic: Q = c S + (foot sliding at fixed velocities), so the c-part
 * da S^T dT/dr S is the damping matrix D (times c = dv/du). */
void ffc__link_friction(const lgeo_t *g, const ffc_link_state *st, const double Dm[][3], double c,
                        const ffc_fric *f, int material_only,
                        double R[FFC_MAXDOF], double K[FFC_MAXDOF][FFC_MAXDOF], double F[FFC_MAXDOF])
{
    const int nd = g->nd;
    const double da = st->da;
    double sw[FFC_MAXDOF], Q[3][FFC_MAXDOF];
    ffc__link_slip_deriv(g, Dm, c, material_only, sw, Q);
    for (int k = 0; k < nd; k++) {
        R[k] += da * sw[k] * f->t[k % 3];
        F[k] = da * sw[k] * f->dt_dtn[k % 3];
    }
    if (!K) return;
    if (!material_only) ffc__link_friction_geo(g, da, sw, f->t, K);
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

int ffc__friction_on(const ffc_effects *fx, const ffc_law *law)
{
    return fx->friction && law->mu > 0.0;
}

/* the velocity form's time step and dv/du: dt > 0, dvdu >= 0, finite */
int ffc__dynamic_ok(const ffc_law *law)
{
    return law->dt > 0 && isfinite(law->dt) && law->dvdu >= 0 && isfinite(law->dvdu);
}
