/* ffc_geom.c: shape functions, local geometry and Gauss rules of 3- and
 * 6-node triangle facets; status strings. */
#include "ffc.h"
#include "ffc_internal.h"

#include <math.h>

const char *ffc_strerror(int status)
{
    switch (status) {
    case FFC_OK: return "success";
    case FFC_INFO_EDGE: return "projection foot clamped onto a facet edge";
    case FFC_INFO_VERTEX: return "projection foot clamped onto a facet vertex";
    case FFC_ERR_NULL: return "a required array is missing (NULL)";
    case FFC_ERR_SIZE: return "array size or count out of range";
    case FFC_ERR_NONFINITE: return "NaN or Inf in input";
    case FFC_ERR_DEGENERATE: return "degenerate (zero-area) facet";
    case FFC_ERR_NODES: return "nodes per facet must be 3 or 6";
    case FFC_ERR_QUAD: return "no quadrature rule of that degree (1..6)";
    case FFC_ERR_NOCONV: return "iteration did not converge";
    case FFC_ERR_CAPACITY: return "output buffer too small";
    case FFC_ERR_EMPTY: return "empty surface or set";
    case FFC_ERR_INDEX: return "node index out of range";
    case FFC_ERR_LABEL: return "no boundary face carries this label";
    case FFC_ERR_VALUE: return "parameter outside its admissible range";
    case FFC_ERR_MEMORY: return "out of memory";
    case FFC_ERR_INVERTED: return "inverted element (signed volume reversed or zero)";
    case FFC_ERR_SINGULAR: return "singular linear system (zero pivot)";
    case FFC_ERR_FUSED: return "slave and master surfaces share their nodes";
    case FFC_ERR_UNAVAILABLE: return "this build lacks the engine asked for (MPI, parallel MUMPS)";
    case FFC_ERR_INTERIOR: return "a contact facet lies inside the mesh (two tetrahedra share it)";
    default: return "unknown status";
    }
}

int ffc_shape(int nn, const double xi[2], double N[FFC_MAXNODES],
              double dN[FFC_MAXNODES][2])
{
    if (nn != 3 && nn != 6) return FFC_ERR_NODES;
    const double s = xi[0], t = xi[1], L1 = 1.0 - s - t;
    if (nn == 3) {
        N[0] = L1; N[1] = s; N[2] = t;
        if (dN) {
            dN[0][0] = -1.0; dN[0][1] = -1.0;
            dN[1][0] = 1.0;  dN[1][1] = 0.0;
            dN[2][0] = 0.0;  dN[2][1] = 1.0;
        }
        return FFC_OK;
    }
    N[0] = L1 * (2.0 * L1 - 1.0);
    N[1] = s * (2.0 * s - 1.0);
    N[2] = t * (2.0 * t - 1.0);
    N[3] = 4.0 * L1 * s;
    N[4] = 4.0 * s * t;
    N[5] = 4.0 * t * L1;
    if (dN) {
        dN[0][0] = 1.0 - 4.0 * L1;     dN[0][1] = 1.0 - 4.0 * L1;
        dN[1][0] = 4.0 * s - 1.0;      dN[1][1] = 0.0;
        dN[2][0] = 0.0;                dN[2][1] = 4.0 * t - 1.0;
        dN[3][0] = 4.0 * (L1 - s);     dN[3][1] = -4.0 * s;
        dN[4][0] = 4.0 * t;            dN[4][1] = 4.0 * s;
        dN[5][0] = -4.0 * t;           dN[5][1] = 4.0 * (L1 - t);
    }
    return FFC_OK;
}

int ffc_shape_d2(int nn, const double xi[2], double d2N[FFC_MAXNODES][3])
{
    (void)xi;
    if (nn != 3 && nn != 6) return FFC_ERR_NODES;
    for (int a = 0; a < nn; a++) d2N[a][0] = d2N[a][1] = d2N[a][2] = 0.0;
    if (nn == 3) return FFC_OK;
    /* second derivatives of the quadratic shapes are constant */
    d2N[0][0] = 4.0; d2N[0][1] = 4.0; d2N[0][2] = 4.0;
    d2N[1][0] = 4.0;
    d2N[2][2] = 4.0;
    d2N[3][0] = -8.0; d2N[3][1] = -4.0;
    d2N[4][1] = 4.0;
    d2N[5][1] = -4.0; d2N[5][2] = -8.0;
    return FFC_OK;
}

/* Squared size of a facet: largest squared vertex-to-vertex distance. */
double ffc__facet_size2(const double X[][3])
{
    double h2 = 0.0;
    for (int a = 0; a < 3; a++) {
        const double *p = X[a], *q = X[(a + 1) % 3];
        double d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
        double l2 = ffc__dot(d, d);
        if (l2 > h2) h2 = l2;
    }
    return h2;
}

int ffc_facet_point(int nn, const double X[][3], const double xi[2],
                    ffc_point *p)
{
    double N[FFC_MAXNODES], dN[FFC_MAXNODES][2];
    int st = ffc_shape(nn, xi, N, dN);
    if (st) return st;
    for (int i = 0; i < 3; i++) {
        p->x[i] = p->tau[0][i] = p->tau[1][i] = 0.0;
        for (int a = 0; a < nn; a++) {
            p->x[i] += N[a] * X[a][i];
            p->tau[0][i] += dN[a][0] * X[a][i];
            p->tau[1][i] += dN[a][1] * X[a][i];
        }
    }
    double c[3];
    ffc__cross(p->tau[0], p->tau[1], c);
    p->j = sqrt(ffc__dot(c, c));
    p->m[0][0] = ffc__dot(p->tau[0], p->tau[0]);
    p->m[0][1] = p->m[1][0] = ffc__dot(p->tau[0], p->tau[1]);
    p->m[1][1] = ffc__dot(p->tau[1], p->tau[1]);
    const double h2 = ffc__facet_size2(X);
    if (!(p->j > FFC__DEGEN_REL * h2)) { /* also catches NaN */
        p->n[0] = p->n[1] = p->n[2] = 0.0;
        p->minv[0][0] = p->minv[0][1] = p->minv[1][0] = p->minv[1][1] = 0.0;
        return isfinite(p->j) ? FFC_ERR_DEGENERATE : FFC_ERR_NONFINITE;
    }
    for (int i = 0; i < 3; i++) p->n[i] = c[i] / p->j;
    const double det = p->j * p->j; /* det m = |tau1 x tau2|^2 */
    p->minv[0][0] = p->m[1][1] / det;
    p->minv[1][1] = p->m[0][0] / det;
    p->minv[0][1] = p->minv[1][0] = -p->m[0][1] / det;
    return FFC_OK;
}

/* ------------------------------------------------------------ quadrature */
/* Symmetric rules (Strang-Fix / Dunavant), weights normalised to area 1. */
typedef struct { double a, b, w; int orbit; } ffc__qorbit;
/* orbit 1: centroid; orbit 3: (a, a, 1-2a) permutations; orbit 6: all
 * permutations of (a, b, 1-a-b). */

static int ffc__qfill(const ffc__qorbit *o, int no, double xi[][2], double w[])
{
    int k = 0;
    for (int i = 0; i < no; i++) {
        const double a = o[i].a, b = o[i].b, ww = 0.5 * o[i].w;
        if (o[i].orbit == 1) {
            xi[k][0] = 1.0 / 3.0; xi[k][1] = 1.0 / 3.0; w[k++] = ww;
        } else if (o[i].orbit == 3) {
            const double c = 1.0 - 2.0 * a;
            xi[k][0] = a; xi[k][1] = a; w[k++] = ww;
            xi[k][0] = c; xi[k][1] = a; w[k++] = ww;
            xi[k][0] = a; xi[k][1] = c; w[k++] = ww;
        } else {
            const double c = 1.0 - a - b;
            const double pts[6][2] = {{a, b}, {b, a}, {a, c}, {c, a}, {b, c}, {c, b}};
            for (int j = 0; j < 6; j++) {
                xi[k][0] = pts[j][0]; xi[k][1] = pts[j][1]; w[k++] = ww;
            }
        }
    }
    return k;
}

static const ffc__qorbit ffc__q1[] = {{0, 0, 1.0, 1}};
static const ffc__qorbit ffc__q2[] = {{1.0 / 6.0, 0, 1.0 / 3.0, 3}};
static const ffc__qorbit ffc__q4[] = {
    {0.445948490915964886318329253883, 0, 0.223381589678011465944827736362, 3},
    {0.091576213509770743459571463402, 0, 0.109951743655321867388505596971, 3}};
/* degree 5: a = (6 -+ sqrt 15)/21, w = (155 -+ sqrt 15)/1200 */
static const ffc__qorbit ffc__q5[] = {
    {0, 0, 0.225, 1},
    {0.101286507323456338800987361915, 0, 0.125939180544827152595683945501, 3},
    {0.470142064105115089770441209513, 0, 0.132394152788506180737649387832, 3}};
static const ffc__qorbit ffc__q6[] = {
    {0.063089014491502228340331602871, 0, 0.050844906370206816920936809107, 3},
    {0.249286745170910421291638553107, 0, 0.116786275726379366030690538690, 3},
    {0.053145049844816947353249671631, 0.310352451033784405416607733956,
     0.082851075618373575193553456421, 6}};

static const ffc__qorbit *ffc__qrule(int degree, int *no)
{
    switch (degree) {
    case 1: *no = 1; return ffc__q1;
    case 2: *no = 1; return ffc__q2;
    case 3: /* fallthrough: the degree-4 rule has positive weights */
    case 4: *no = 2; return ffc__q4;
    case 5: *no = 3; return ffc__q5;
    case 6: *no = 3; return ffc__q6;
    default: *no = 0; return 0;
    }
}

int ffc_quad_size(int degree)
{
    int no;
    const ffc__qorbit *o = ffc__qrule(degree, &no);
    if (!o) return FFC_ERR_QUAD;
    int n = 0;
    for (int i = 0; i < no; i++) n += o[i].orbit;
    return n;
}

int ffc_quad(int degree, int cap, double xi[][2], double w[])
{
    int no;
    const ffc__qorbit *o = ffc__qrule(degree, &no);
    if (!o) return FFC_ERR_QUAD;
    if (!xi || !w) return FFC_ERR_NULL;
    if (cap < ffc_quad_size(degree)) return FFC_ERR_CAPACITY;
    return ffc__qfill(o, no, xi, w);
}
