/* ffc_link_internal.h: types and functions shared by the contact-law
 * kernels (ffc_normal.c, ffc_friction.c, ffc_assemble.c, ffc_nodal.c,
 * ffc_nodal_assemble.c, ffc_augment.c, ffc_points.c); not part of the
 * public interface. */
#ifndef FFC_LINK_INTERNAL_H
#define FFC_LINK_INTERNAL_H

#include "ffc.h"

/* a law's tangent without the geometric terms (material or ranked) */
static inline int ffc__law_material(const ffc_law *law)
{
    return law->tangent == FFC_TANGENT_MATERIAL || law->tangent == FFC_TANGENT_RANKED;
}

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
    double dm[3];                   /* a rigid obstacle's motion at the foot (ffc_obstacle.d; 0 for facets) */
} lgeo_t;

/* The facets of one link, gathered. */
typedef struct {
    double Xs[FFC_MAXNODES][3], Xs0[FFC_MAXNODES][3], Ds[FFC_MAXNODES][3];
    double Xm[FFC_MAXNODES][3], Xm0[FFC_MAXNODES][3], Dm[FFC_MAXNODES][3];
    long dof[FFC_MAXDOF];
    int nd;
} lnodes_t;

#define CP3(a) ((const double(*)[3])(a))

/* weight of a link's point: the rule's (q >= 0) or its own (segment links, q = -1) */
static inline double ffc__link_weight(const ffc_link *lk, const double qw[])
{
    return lk->q < 0 ? lk->w : qw[lk->q];
}

/* Nodal (mortar-type) law, see the Formulation comment in ffc_nodal.c.
 * A linked point: */
typedef struct {
    long k;                 /* link index */
    int nd;                 /* unknowns */
    double g, da;           /* gap, point area */
    double n[3];            /* master normal at the foot */
    double N[FFC_MAXNODES]; /* slave (multiplier) shape values at the point */
    double Nt[FFC_MAXNODES]; /* ... of the friction sums (law->tdual: the dual basis; else N) */
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
    int drop;                   /* bit k: direction e_k dropped (prescribed, in the contact plane) */
    ffc_fric f;                 /* traction T_a and its derivatives */
} nfn_t;

/* the nodal law evaluated over a pair (ffc__nodal_prepare) */
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

/* ffc_normal.c: geometry of one link (D = dG/du when D != NULL; xm0: a
 * foot found before, the start of a curved master's projection, or NULL;
 * ob: a rigid obstacle as the master, with nm = 0, or NULL) */
int ffc__link_geometry(const ffc_effects *fx, int ns, const double Xs[][3], const double Xs0[][3],
                       const double xs[2], double w, int nm, const double Xm[][3], const double xm0[2],
                       const ffc_obstacle *ob, ffc_link_state *st, lgeo_t *g, double D[FFC_MAXDOF][FFC_MAXDOF]);

/* ffc_normal.c: ffc_link_contact and ffc_link_obstacle (ob: the obstacle with nm = 0 and Xm, Dm unused) */
int ffc__link_contact(const ffc_effects *effects, int ns, const double Xs[][3], const double Xs0[][3],
                      const double Ds[][3], const double xs[2], double w, int nm, const double Xm[][3],
                      const double Dm[][3], const ffc_obstacle *ob, double lambda, const double lam_t[3],
                      const ffc_law *law, ffc_link_state *st, double R[FFC_MAXDOF], double K[FFC_MAXDOF][FFC_MAXDOF]);

/* ffc_friction.c: the slip r of a link and its derivative Q = dr/du */
void ffc__link_slip(const lgeo_t *g, const double Ds[][3], const double Dm[][3], double r[3]);
void ffc__link_slip_deriv(const lgeo_t *g, const double Dm[][3], double c, int material_only,
                          double sw[FFC_MAXDOF], double Q[3][FFC_MAXDOF]);
/* dD/du of the friction motion, and the factor from the map's r to the slip over the step */
double ffc__motion_coef(const ffc_effects *fx, const ffc_law *law);
double ffc__slip_scale(const ffc_effects *fx, const ffc_law *law);
/* friction terms of one link at fixed traction T (foot sliding, area) */
void ffc__link_friction_geo(const lgeo_t *g, double da, const double sw[FFC_MAXDOF], const double T[3],
                            double K[FFC_MAXDOF][FFC_MAXDOF]);
/* pointwise friction residual and tangent of one link; F = da S^T dT/dt_N */
void ffc__link_friction(const lgeo_t *g, const ffc_link_state *st, const double Dm[][3], double c,
                        const ffc_fric *f, int material_only,
                        double R[FFC_MAXDOF], double K[FFC_MAXDOF][FFC_MAXDOF], double F[FFC_MAXDOF]);
/* friction on (effects->friction and mu > 0); the velocity form's dt, dvdu valid */
int ffc__friction_on(const ffc_effects *fx, const ffc_law *law);
int ffc__dynamic_ok(const ffc_law *law);

/* ffc_assemble.c: a link's nodes gathered, a link evaluated (pointwise law),
 * statistics, the checks every call over all links shares */
int ffc__gather_link(const ffc_effects *fx, const ffc_pair *P, int nq, const ffc_link *lk, lnodes_t *n);
int ffc__eval_link(const ffc_effects *fx, const ffc_pair *P, const double qw[], int nq,
                   const ffc_link *lk, double lambda, const double lam_t[3], const ffc_law *law,
                   ffc_link_state *st, double R[FFC_MAXDOF], double K[FFC_MAXDOF][FFC_MAXDOF],
                   long dof[FFC_MAXDOF], int *nd);
void ffc__stats_init(ffc_stats *s);
void ffc__stats_pressure(ffc_stats *s, double t, double da, const double n[3]);
double ffc__tangential_norm(const double r[3], const double n[3]);
void ffc__stats_add(ffc_stats *s, const ffc_link_state *st, int fric);
int ffc__common_checks(const ffc_effects *fx, const ffc_pair *P, int qdeg, long nl,
                       const ffc_link links[], const ffc_law *law, const double lambda[],
                       const double lam_t[], double qw[16], int *nq, long *bad);

/* ffc_nodal.c: the nodal law's work (prepare, free), its multiplier shape
 * values at a point xs of slave facet f (N[ns]), its values at a linked
 * point; ffc_nodal_assemble.c: its assembly */
void ffc__nodal_free(nodal_t *w);
int ffc__nodal_prepare(const ffc_effects *fx, const ffc_pair *P, const double qw[], int nq, long nl,
                       const ffc_link links[], const double lambda[], const double lam_t[], const ffc_law *law,
                       nodal_t *w, ffc_stats *stats, long *bad);
void ffc__nodal_shape(const ffc_law *law, int ns, long f, const double xs[2], double N[FFC_MAXNODES]);
double ffc__nodal_point_pressure(const ffc_pair *P, const ffc_link *lk, const nlink_t *e, const double tn[]);
void ffc__nodal_point_traction(const ffc_pair *P, const ffc_link *lk, const nlink_t *e, const nfn_t T[],
                               double t[3], int *state);
void ffc__nodal_point_stats(ffc_stats *s, double t, const nlink_t *e, const double Tq[3]);
int ffc__assemble_nodal(const ffc_effects *fx, const ffc_pair *P, const double qw[], int nq, long nl,
                        const ffc_link links[], const double lambda[], const double lam_t[],
                        const ffc_law *law, double R[], long cap, long Ti[], long Tj[], double Tv[],
                        long *ntrip, ffc_stats *stats, long *bad);

#endif
