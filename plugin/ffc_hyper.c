/* ffc_hyper.c: hyperelastic bulk operators on tetrahedra: the pointwise laws (energy, first Piola-Kirchhoff stress, its derivative) and their internal force and tangent assembled on a fixed pattern. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ffc.h"
#include "ffc_internal.h"

/* det F and B = F^-1 (row-major: B[3 r + c]) */
static double inverse3(const double F[9], double B[9])
{
    const double c00 = F[4] * F[8] - F[5] * F[7], c01 = F[5] * F[6] - F[3] * F[8], c02 = F[3] * F[7] - F[4] * F[6];
    const double J = F[0] * c00 + F[1] * c01 + F[2] * c02;
    B[0] = c00 / J; B[3] = c01 / J; B[6] = c02 / J;
    B[1] = (F[2] * F[7] - F[1] * F[8]) / J;
    B[4] = (F[0] * F[8] - F[2] * F[6]) / J;
    B[7] = (F[1] * F[6] - F[0] * F[7]) / J;
    B[2] = (F[1] * F[5] - F[2] * F[4]) / J;
    B[5] = (F[2] * F[3] - F[0] * F[5]) / J;
    B[8] = (F[0] * F[4] - F[1] * F[3]) / J;
    return J;
}

/* Formulation (compressible Neo-Hookean): with J = det F, B = F^-1,
 *     W = mu / 2 (F : F - 3) - mu ln J + lambda / 2 (ln J)^2,
 *     P = dW/dF = mu (F - F^-T) + lambda ln J F^-T,
 * and, from d(F^-T)_iJ / dF_kL = -B_Jk B_Li and d ln J / dF_kL = B_Lk,
 *     A_iJkL = dP_iJ / dF_kL
 *            = mu d_ik d_JL + (mu - lambda ln J) B_Jk B_Li + lambda B_Ji B_Lk.
 * Defined for J > 0 only. */
static int neohookean(double lam, double mu, const double F[9], double *W, double P[9], double A[81])
{
    double B[9];
    const double J = inverse3(F, B);
    if (!(J > 0) || !isfinite(J)) return FFC_ERR_INVERTED;
    const double L = log(J), c = mu - lam * L;
    double ff = 0;
    for (int k = 0; k < 9; k++) ff += F[k] * F[k];
    *W = 0.5 * mu * (ff - 3.0) - mu * L + 0.5 * lam * L * L;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) P[3 * i + j] = mu * F[3 * i + j] - c * B[3 * j + i];
    if (!A) return FFC_OK;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++)
                for (int l = 0; l < 3; l++)
                    A[27 * i + 9 * j + 3 * k + l] = (i == k && j == l ? mu : 0.0) + c * B[3 * j + k] * B[3 * l + i]
                                                    + lam * B[3 * j + i] * B[3 * l + k];
    return FFC_OK;
}

/* Formulation (Saint Venant-Kirchhoff): E = (F^T F - I) / 2,
 *     W = lambda / 2 (tr E)^2 + mu E : E,  S = lambda tr E I + 2 mu E,  P = F S,
 * and, from dE_MN / dF_kL = (d_NL F_kM + d_ML F_kN) / 2,
 *     A_iJkL = d_ik S_JL + lambda F_iJ F_kL + mu d_JL (F F^T)_ik + mu F_iL F_kJ.
 * Defined for every F (it softens under strong compression). */
static int svk(double lam, double mu, const double F[9], double *W, double P[9], double A[81])
{
    double E[9], S[9], FFt[9];
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
            double c = 0, d = 0;
            for (int k = 0; k < 3; k++) { c += F[3 * k + a] * F[3 * k + b]; d += F[3 * a + k] * F[3 * b + k]; }
            E[3 * a + b] = 0.5 * (c - (a == b));
            FFt[3 * a + b] = d;
        }
    const double tr = E[0] + E[4] + E[8];
    double ee = 0;
    for (int k = 0; k < 9; k++) { ee += E[k] * E[k]; S[k] = 2.0 * mu * E[k]; }
    S[0] += lam * tr; S[4] += lam * tr; S[8] += lam * tr;
    *W = 0.5 * lam * tr * tr + mu * ee;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            P[3 * i + j] = F[3 * i] * S[j] + F[3 * i + 1] * S[3 + j] + F[3 * i + 2] * S[6 + j];
    if (!A) return FFC_OK;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++)
                for (int l = 0; l < 3; l++)
                    A[27 * i + 9 * j + 3 * k + l] = (i == k ? S[3 * j + l] : 0.0) + lam * F[3 * i + j] * F[3 * k + l]
                                                    + (j == l ? mu * FFt[3 * i + k] : 0.0) + mu * F[3 * i + l] * F[3 * k + j];
    return FFC_OK;
}

/* Formulation (compressible Mooney-Rivlin): with C = F^T F, b = F F^T,
 * I1 = tr C, I2 = (I1^2 - C : C) / 2, J = det F, B = F^-1, and the
 * constants c10 = mu / 2 - c01, lambda' = lambda - 4 c01 (so that its
 * linearization at F = I is linear elasticity of lambda and mu),
 *     W = c10 (I1 - 3) + c01 (I2 - 3) - 2 (c10 + 2 c01) ln J + lambda' / 2 (ln J)^2,
 * the Neo-Hookean law of lambda' and 2 c10 plus W2 = c01 (I2 - 3) - 4 c01 ln J:
 * from dI1 / dF = 2 F and dI2 / dF = 2 (I1 F - F C),
 *     P2 = 2 c01 (I1 F - F C) - 4 c01 F^-T,
 * and from d(F C)_iJ / dF_kL = d_ik C_LJ + F_iL F_kJ + b_ik d_JL,
 *     A2_iJkL = 2 c01 (2 F_iJ F_kL + I1 d_ik d_JL - d_ik C_LJ - F_iL F_kJ
 *               - b_ik d_JL) + 4 c01 B_Jk B_Li.
 * (Small strain: I1 - 3 - 2 ln J = 2 eps : eps and I2 - 3 - 4 ln J =
 * 2 eps : eps + 2 (tr eps)^2, to second order.)  Defined for J > 0 and
 * 0 <= c01 <= mu / 2 (c10 >= 0). */
static int mooneyrivlin(double lam, double mu, double c01, const double F[9], double *W, double P[9], double A[81])
{
    if (!(c01 >= 0) || !(c01 <= 0.5 * mu)) return FFC_ERR_VALUE;
    const double c10 = 0.5 * mu - c01;
    int st = neohookean(lam - 4.0 * c01, 2.0 * c10, F, W, P, A);
    if (st || c01 == 0) return st;
    double B[9], C[9], b[9];
    const double J = inverse3(F, B);
    for (int a = 0; a < 3; a++)
        for (int c = 0; c < 3; c++) {
            double x = 0, y = 0;
            for (int k = 0; k < 3; k++) { x += F[3 * k + a] * F[3 * k + c]; y += F[3 * a + k] * F[3 * c + k]; }
            C[3 * a + c] = x;
            b[3 * a + c] = y;
        }
    const double I1 = C[0] + C[4] + C[8];
    double CC = 0;
    for (int k = 0; k < 9; k++) CC += C[k] * C[k];
    const double I2 = 0.5 * (I1 * I1 - CC);
    *W += c01 * (I2 - 3.0) - 4.0 * c01 * log(J);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            const double FC = F[3 * i] * C[j] + F[3 * i + 1] * C[3 + j] + F[3 * i + 2] * C[6 + j];
            P[3 * i + j] += 2.0 * c01 * (I1 * F[3 * i + j] - FC) - 4.0 * c01 * B[3 * j + i];
        }
    if (!A) return FFC_OK;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++)
                for (int l = 0; l < 3; l++)
                    A[27 * i + 9 * j + 3 * k + l] +=
                        2.0 * c01 * (2.0 * F[3 * i + j] * F[3 * k + l] + (i == k && j == l ? I1 : 0.0)
                                     - (i == k ? C[3 * l + j] : 0.0) - F[3 * i + l] * F[3 * k + j] - (j == l ? b[3 * i + k] : 0.0))
                        + 4.0 * c01 * B[3 * j + k] * B[3 * l + i];
    return FFC_OK;
}

int ffc_hyper_point(int law, double lam, double mu, double c01, const double F[9], double *W, double P[9], double A[81])
{
    if (!F || !W || !P) return FFC_ERR_NULL;
    for (int k = 0; k < 9; k++)
        if (!isfinite(F[k])) return FFC_ERR_NONFINITE;
    if (!isfinite(lam) || !isfinite(mu) || !isfinite(c01)) return FFC_ERR_NONFINITE;
    if (law == FFC_HYPER_NEOHOOKEAN) return neohookean(lam, mu, F, W, P, A);
    if (law == FFC_HYPER_SVK) return svk(lam, mu, F, W, P, A);
    if (law == FFC_HYPER_MOONEYRIVLIN) return mooneyrivlin(lam, mu, c01, F, W, P, A);
    return FFC_ERR_VALUE;
}

static int fail(ffc_error *err, int st, ffc_where where, long index, const char *msg)
{
    if (err) {
        err->status = st;
        err->where = where;
        err->index = index;
        snprintf(err->msg, sizeof err->msg, "%s", msg);
    }
    return st;
}

/* the mesh's arrays and indices (the checks every call makes first) */
static int check_tets(const ffc_tets *m, ffc_error *err)
{
    char msg[200];
    if (!m) return fail(err, FFC_ERR_NULL, FFC_AT_NONE, -1, "no mesh");
    if (m->nv < 0 || m->nt < 0 || m->nn < 0 || (m->npe != 4 && m->npe != 10)) {
        snprintf(msg, sizeof msg, "mesh sizes: %ld vertices, %ld tetrahedra, %ld nodes, %ld nodes per tetrahedron (4 or 10)",
                 m->nv, m->nt, m->nn, m->npe);
        return fail(err, FFC_ERR_SIZE, FFC_AT_NONE, -1, msg);
    }
    if ((m->nv > 0 && !m->X) || (m->nt > 0 && (!m->T || !m->E))) return fail(err, FFC_ERR_NULL, FFC_AT_NONE, -1, "mesh arrays missing");
    for (long t = 0; t < m->nt; t++) {
        for (int a = 0; a < 4; a++)
            if (m->T[4 * t + a] < 0 || m->T[4 * t + a] >= m->nv) {
                snprintf(msg, sizeof msg, "tetrahedron %ld: vertex %ld outside [0, %ld)", t, m->T[4 * t + a], m->nv);
                return fail(err, FFC_ERR_INDEX, FFC_AT_ELEMENT, t, msg);
            }
        for (long a = 0; a < m->npe; a++)
            if (m->E[m->npe * t + a] < 0 || m->E[m->npe * t + a] >= m->nn) {
                snprintf(msg, sizeof msg, "tetrahedron %ld: node %ld outside [0, %ld)", t, m->E[m->npe * t + a], m->nn);
                return fail(err, FFC_ERR_INDEX, FFC_AT_ELEMENT, t, msg);
            }
    }
    return FFC_OK;
}

int ffc_tets_pattern(const ffc_tets *m, long cap, long rp[], long adj[], long *nb, ffc_error *err)
{
    if (err) *err = (ffc_error){0, FFC_AT_NONE, -1, ""};
    if (!nb || !rp || (cap > 0 && !adj)) return fail(err, FFC_ERR_NULL, FFC_AT_NONE, -1, "no output array");
    *nb = 0;
    int st = check_tets(m, err);
    if (st) return st;
    if (cap < 0) return fail(err, FFC_ERR_SIZE, FFC_AT_NONE, -1, "a negative capacity");
    const long npe = m->npe, nn = m->nn;
    long *w = malloc((size_t)(npe * (npe - 1) * m->nt + nn + 1) * sizeof *w), *fill = malloc(((size_t)nn + 1) * sizeof *fill);
    if (!w || !fill) {
        free(w); free(fill);
        return fail(err, FFC_ERR_MEMORY, FFC_AT_COUNT, npe * (npe - 1) * m->nt + nn + 1, "out of memory for the node graph");
    }
    *nb = ffc__tet_graph(m->nt, npe, nn, m->E, rp, w, fill);
    if (cap >= *nb) memcpy(adj, w, (size_t)*nb * sizeof *adj);
    free(w); free(fill);
    if (cap < *nb) {
        char msg[200];
        snprintf(msg, sizeof msg, "room for %ld node pairs, %ld needed", cap, *nb);
        return fail(err, FFC_ERR_CAPACITY, FFC_AT_COUNT, *nb, msg);
    }
    return FFC_OK;
}

void ffc_tets_pattern_ij(long nn, const long rp[], const long adj[], long Ki[], long Kj[])
{
    for (long i = 0; i < nn; i++) {
        const long k = rp[i + 1] - rp[i];
        for (int ci = 0; ci < 3; ci++) {
            const long r0 = 9 * rp[i] + 3 * ci * k;
            for (long e = 0; e < k; e++)
                for (int cj = 0; cj < 3; cj++) {
                    Ki[r0 + 3 * e + cj] = 3 * i + ci;
                    Kj[r0 + 3 * e + cj] = 3 * adj[rp[i] + e] + cj;
                }
        }
    }
}

/* Formulation (the discrete operator): u = sum_a N_a u_a, F = I + sum_a
 * u_a (x) grad N_a at each quadrature point x_q of weight w_q; the
 * internal force on node a, component i, is
 *     f_ai = sum_q w_q P_iJ(F_q) G_a[J]                 (G_a = grad N_a),
 * and its derivative along node b, component k (A = dP/dF),
 *     K_ai,bk = sum_q w_q G_a[J] A_iJkL(F_q) G_b[L],
 * symmetric as A_iJkL = A_kLiJ for a stored energy.  P1: one point at the
 * centroid (F is constant); P2: the 14-point rule of degree 5. */
int ffc_hyper_assemble(int law, const ffc_tets *m, const double lam[], const double mu[], const double c01[],
                       const double u[], const long rp[], const long adj[], double *W, double f[], double Kv[],
                       ffc_error *err)
{
    char msg[200];
    if (err) *err = (ffc_error){0, FFC_AT_NONE, -1, ""};
    int st = check_tets(m, err);
    if (st) return st;
    if (law != FFC_HYPER_NEOHOOKEAN && law != FFC_HYPER_SVK && law != FFC_HYPER_MOONEYRIVLIN) {
        snprintf(msg, sizeof msg, "law %d: not FFC_HYPER_NEOHOOKEAN, FFC_HYPER_SVK or FFC_HYPER_MOONEYRIVLIN", law);
        return fail(err, FFC_ERR_VALUE, FFC_AT_NONE, -1, msg);
    }
    const int mr = law == FFC_HYPER_MOONEYRIVLIN;
    if ((m->nt > 0 && (!lam || !mu || (mr && !c01))) || (m->nn > 0 && !u) || (Kv && (!rp || !adj)))
        return fail(err, FFC_ERR_NULL, FFC_AT_NONE, -1, "a required array is missing");
    const long nt = m->nt, npe = m->npe, nn = m->nn;
    for (long t = 0; t < nt; t++) {
        if (!isfinite(lam[t]) || !isfinite(mu[t]) || (mr && !isfinite(c01[t]))) {
            snprintf(msg, sizeof msg, "tetrahedron %ld: Lame's constants %g, %g, c01 %g", t, lam[t], mu[t], mr ? c01[t] : 0.0);
            return fail(err, FFC_ERR_NONFINITE, FFC_AT_ELEMENT, t, msg);
        }
        if (mr && !(c01[t] >= 0 && c01[t] <= 0.5 * mu[t])) {
            snprintf(msg, sizeof msg, "tetrahedron %ld: c01 = %g is outside [0, mu / 2 = %g]", t, c01[t], 0.5 * mu[t]);
            return fail(err, FFC_ERR_VALUE, FFC_AT_ELEMENT, t, msg);
        }
    }
    for (long k = 0; k < 3 * nn; k++)
        if (!isfinite(u[k])) {
            snprintf(msg, sizeof msg, "displacement dof %ld is %g", k, u[k]);
            return fail(err, FFC_ERR_NONFINITE, FFC_AT_DOF, k, msg);
        }
    for (long k = 0; k < 3 * m->nv; k++)
        if (!isfinite(m->X[k])) {
            snprintf(msg, sizeof msg, "vertex %ld: a coordinate is %g", k / 3, m->X[k]);
            return fail(err, FFC_ERR_NONFINITE, FFC_AT_NODE, k / 3, msg);
        }
    if (W) *W = 0;
    if (f) memset(f, 0, (size_t)(3 * nn) * sizeof *f);
    if (Kv) memset(Kv, 0, (size_t)(9 * rp[nn]) * sizeof *Kv);
    double Lq[14][4], wq[14];
    int nq = 1;
    if (npe == 4) { Lq[0][0] = Lq[0][1] = Lq[0][2] = Lq[0][3] = 0.25; wq[0] = 1.0; }
    else nq = ffc__tet_rule5(Lq, wq);
    for (long t = 0; t < nt; t++) {
        double g[4][3], V;
        if (ffc__tet_gradients(m->X, m->T + 4 * t, g, &V)) {
            snprintf(msg, sizeof msg, "tetrahedron %ld has no volume", t);
            return fail(err, FFC_ERR_DEGENERATE, FFC_AT_ELEMENT, t, msg);
        }
        const long *nd = m->E + npe * t;
        long pos[10][10]; /* block position of node b in node a's row */
        if (Kv)
            for (long a = 0; a < npe; a++)
                for (long b = 0; b < npe; b++) {
                    const long i = nd[a], k = rp[i + 1] - rp[i], e = ffc__find_long(adj + rp[i], k, nd[b]);
                    if (k <= 0 || adj[rp[i] + e] != nd[b]) {
                        snprintf(msg, sizeof msg, "tetrahedron %ld: nodes %ld and %ld are not in the pattern", t, i, nd[b]);
                        return fail(err, FFC_ERR_INDEX, FFC_AT_ELEMENT, t, msg);
                    }
                    pos[a][b] = e;
                }
        for (int q = 0; q < nq; q++) {
            double G[10][3], F[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, P[9], A[81], Wq;
            ffc__tet_shape_gradients(npe, (const double(*)[3])g, Lq[q], G);
            for (long a = 0; a < npe; a++) {
                const double *ua = u + 3 * nd[a];
                for (int i = 0; i < 3; i++)
                    for (int j = 0; j < 3; j++) F[3 * i + j] += ua[i] * G[a][j];
            }
            st = law == FFC_HYPER_NEOHOOKEAN ? neohookean(lam[t], mu[t], F, &Wq, P, Kv ? A : NULL)
                 : law == FFC_HYPER_SVK      ? svk(lam[t], mu[t], F, &Wq, P, Kv ? A : NULL)
                                             : mooneyrivlin(lam[t], mu[t], c01[t], F, &Wq, P, Kv ? A : NULL);
            if (st) {
                snprintf(msg, sizeof msg, "tetrahedron %ld is inverted (det F <= 0 at a quadrature point)", t);
                return fail(err, st, FFC_AT_ELEMENT, t, msg);
            }
            const double w = wq[q] * V;
            if (W) *W += w * Wq;
            if (f)
                for (long a = 0; a < npe; a++)
                    for (int i = 0; i < 3; i++)
                        f[3 * nd[a] + i] += w * (P[3 * i] * G[a][0] + P[3 * i + 1] * G[a][1] + P[3 * i + 2] * G[a][2]);
            if (!Kv) continue;
            for (long b = 0; b < npe; b++) {
                double AG[3][3][3]; /* AG[i][J][k] = w A_iJkL G_b[L] */
                for (int i = 0; i < 3; i++)
                    for (int j = 0; j < 3; j++)
                        for (int k = 0; k < 3; k++) {
                            const double *a4 = A + 27 * i + 9 * j + 3 * k;
                            AG[i][j][k] = w * (a4[0] * G[b][0] + a4[1] * G[b][1] + a4[2] * G[b][2]);
                        }
                for (long a = 0; a < npe; a++) {
                    const long i0 = nd[a], k0 = rp[i0 + 1] - rp[i0];
                    for (int i = 0; i < 3; i++) {
                        double *row = Kv + 9 * rp[i0] + 3 * i * k0 + 3 * pos[a][b];
                        for (int k = 0; k < 3; k++)
                            row[k] += G[a][0] * AG[i][0][k] + G[a][1] * AG[i][1][k] + G[a][2] * AG[i][2][k];
                    }
                }
            }
        }
    }
    return FFC_OK;
}
