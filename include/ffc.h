/* ffc.h: public C interface of the ffcontact kernels (3D contact geometry,
 * contact search and contact links for FreeFEM), free of FreeFEM types. */
#ifndef FFC_H
#define FFC_H

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------- status */
/* Negative = error, 0 = success, positive = information. */
enum {
    FFC_OK = 0,
    FFC_INFO_EDGE = 1,            /* projection foot clamped onto a facet edge */
    FFC_INFO_VERTEX = 2,          /* projection foot clamped onto a facet vertex */
    FFC_ERR_NULL = -1,            /* a required pointer is NULL */
    FFC_ERR_SIZE = -2,            /* an array size or count is out of range */
    FFC_ERR_NONFINITE = -3,       /* NaN or Inf in an input */
    FFC_ERR_DEGENERATE = -4,      /* zero-area facet (|tau1 x tau2| ~ 0) */
    FFC_ERR_NODES = -5,           /* nodes per facet is neither 3 nor 6 */
    FFC_ERR_QUAD = -6,            /* no quadrature rule of that degree */
    FFC_ERR_NOCONV = -7,          /* an iteration did not converge */
    FFC_ERR_CAPACITY = -8,        /* caller buffer too small (needed size returned separately) */
    FFC_ERR_EMPTY = -9,           /* an empty surface or set */
    FFC_ERR_INDEX = -10,          /* a node index out of range */
    FFC_ERR_LABEL = -11,          /* a label that no boundary face carries */
    FFC_ERR_VALUE = -12,          /* a parameter outside its admissible range */
    FFC_ERR_MEMORY = -13,         /* allocation failed */
    FFC_ERR_INVERTED = -14,       /* a facet turned inside out (normal reversed) */
    FFC_ERR_SINGULAR = -15,       /* a linear system is singular (zero pivot) */
    FFC_ERR_FUSED = -16,          /* slave and master surfaces share their nodes */
    FFC_ERR_UNAVAILABLE = -17,    /* this build lacks the engine asked for (MPI, MUMPS) */
    FFC_ERR_INTERIOR = -18        /* a contact facet lies inside the volume mesh (two tetrahedra share it) */
};

/* Human-readable text of a status code (static string, never NULL). */
const char *ffc_strerror(int status);

/* What an error's index counts. */
typedef enum {
    FFC_AT_NONE = 0,   /* no index */
    FFC_AT_DOF,        /* a degree of freedom (3 node + component) */
    FFC_AT_NODE,       /* a node */
    FFC_AT_FACET,      /* a facet of a surface */
    FFC_AT_LINK,       /* a contact link */
    FFC_AT_PAIR,       /* a contact pair */
    FFC_AT_TRIPLET,    /* an entry of a triplet list */
    FFC_AT_COUNT       /* not a position: the count or size needed */
} ffc_where;

/* A failure's record: its status, what failed (an index and what it
 * counts) and a message naming the cause (with sizes where they matter). */
typedef struct {
    int status;        /* a negative FFC_ERR_* (0: none) */
    ffc_where where;   /* what index counts */
    long index;        /* -1: none */
    char msg[200];     /* one line, no trailing newline ("" when none) */
} ffc_error;

/* ------------------------------------------------------ driver settings */
/* The settings of the scene driver (scripts/scene.idp), held by the scene
 * with their defaults and admissible values. */
typedef enum { FFC_SET_INT = 0, FFC_SET_REAL = 1, FFC_SET_WORD = 2 } ffc_set_type;
typedef struct {
    const char *name;     /* as a script names it */
    ffc_set_type type;
    double def, lo, hi;   /* default and admissible range (FFC_SET_WORD: the default word's position) */
    int open;             /* bit 1: lo excluded; bit 2: hi excluded */
    const char *words;    /* FFC_SET_WORD: the admissible words, space-separated (NULL otherwise) */
    const char *what;     /* what it sets (one line) */
} ffc_setting;
enum { FFC_NSETTINGS = 64 };  /* room for the settings (ffc_settings_count() <= this) */
typedef struct {
    double v[FFC_NSETTINGS];  /* by position in the table (a word: its position in the list) */
} ffc_settings;
int ffc_settings_count(void);
/* the i-th setting's description (NULL past the end) */
const ffc_setting *ffc_setting_at(int i);
/* the position of a setting, or FFC_ERR_VALUE */
int ffc_setting_find(const char *name);
void ffc_settings_defaults(ffc_settings *s);
/* A setting's value (a number; a word).  FFC_ERR_VALUE with err->msg
 * naming the setting and the value for an unknown name, a value outside
 * its range, a fraction for a whole number, an unknown word. */
int ffc_settings_set(ffc_settings *s, const char *name, double v, ffc_error *err);
int ffc_settings_set_word(ffc_settings *s, const char *name, const char *w, ffc_error *err);
int ffc_settings_get(const ffc_settings *s, const char *name, double *v);
/* a word setting's word into out[cap] (FFC_ERR_CAPACITY when it does not fit) */
int ffc_settings_word(const ffc_settings *s, const char *name, char *out, long cap);

/* ------------------------------------------------------------- effects */
/* What a scene computes: kernels skip every term whose effect is off. */
typedef struct {
    int friction;      /* 1: Coulomb friction terms, 0: frictionless (none computed) */
    int dynamic;       /* 1: velocity form with time step, 0: quasi-static */
    int finite_def;    /* 1: geometry of the current configuration x = X + u in
                          area elements and tangents, 0: small strain */
} ffc_effects;

/* ---------------------------------------------------- facet shape functions */
/* Triangle facets in local coordinates (xi1, xi2), area coordinates
 * L1 = 1 - xi1 - xi2, L2 = xi1, L3 = xi2.  Node order: 3 vertices at
 * (0,0), (1,0), (0,1); for 6 nodes then the mid-edge nodes of edges
 * 0-1, 1-2, 2-0. */
#define FFC_MAXNODES 6                  /* nodes of the largest facet */
#define FFC_MAXDOF (3 * 2 * FFC_MAXNODES) /* slave + master facet dofs of one link (36) */

/* N[nn] shape values, dN[nn][2] first derivatives d N_a / d xi_b.
 * Returns FFC_OK or FFC_ERR_NODES. */
int ffc_shape(int nn, const double xi[2], double N[FFC_MAXNODES],
              double dN[FFC_MAXNODES][2]);

/* d2N[nn][3] second derivatives (d11, d12, d22); zero for 3 nodes. */
int ffc_shape_d2(int nn, const double xi[2], double d2N[FFC_MAXNODES][3]);

/* Geometry of a facet at one point, in the configuration whose nodal
 * positions are given. */
typedef struct {
    double x[3];        /* position (length) */
    double tau[2][3];   /* covariant tangents dx/dxi_a (length) */
    double n[3];        /* unit normal tau1 x tau2 / |tau1 x tau2| (1) */
    double m[2][2];     /* surface metric m_ab = tau_a . tau_b (length^2) */
    double minv[2][2];  /* inverse metric m^ab (1/length^2) */
    double j;           /* area element |tau1 x tau2| (length^2 per unit xi-area) */
} ffc_point;

/* Position, tangents, normal, metric and area element at xi of the facet
 * with nodal positions X[nn][3].  FFC_ERR_DEGENERATE if j is not positive
 * relative to the square of the facet size. */
int ffc_facet_point(int nn, const double X[][3], const double xi[2],
                    ffc_point *p);

/* ------------------------------------------------------------ quadrature */
/* Gauss rules on the reference triangle (area 1/2), exact for polynomials
 * of total degree <= degree, degree 1..6: 1, 3, 6, 6, 7, 12 points.
 * Returns the number of points needed for degree (or FFC_ERR_QUAD). */
int ffc_quad_size(int degree);

/* Fills xi[npts][2] and w[npts] (weights summing to 1/2). cap is the
 * capacity of both arrays in points.  Returns the number of points,
 * FFC_ERR_QUAD, or FFC_ERR_CAPACITY if cap < ffc_quad_size(degree). */
int ffc_quad(int degree, int cap, double xi[][2], double w[]);

/* ------------------------------------------------------------ projection */
/* Where the foot of a projection lies on the facet. */
enum {
    FFC_FOOT_INSIDE = 0,   /* interior (or on the boundary within round-off) */
    FFC_FOOT_EDGE0 = 1,    /* clamped onto edge 0-1 (xi2 = 0) */
    FFC_FOOT_EDGE1 = 2,    /* clamped onto edge 1-2 (xi1 + xi2 = 1) */
    FFC_FOOT_EDGE2 = 3,    /* clamped onto edge 2-0 (xi1 = 0) */
    FFC_FOOT_VERTEX0 = 4,  /* clamped onto vertex 0 */
    FFC_FOOT_VERTEX1 = 5,
    FFC_FOOT_VERTEX2 = 6
};

/* Closest-point projection of a point p onto a facet. */
typedef struct {
    double xi[2];       /* local coordinates of the foot, inside the facet (1) */
    double xi_free[2];  /* stationary point of |p - x(xi)| without the facet
                           bounds; equals xi when where == FFC_FOOT_INSIDE (1) */
    double x[3];        /* foot position x(xi) (length) */
    double n[3];        /* unit facet normal at the foot (1) */
    double gap;         /* signed normal gap n . (p - x): > 0 on the side the
                           normal points to, < 0 below (length) */
    double dist;        /* |p - x| (length) */
    int where;          /* FFC_FOOT_* */
    int iters;          /* Newton iterations used (0 for flat facets) */
} ffc_proj;

/* Projects p onto the facet X[nn][3].  Returns FFC_OK when the foot is
 * inside, FFC_INFO_EDGE or FFC_INFO_VERTEX when it was clamped onto the
 * boundary (out->where says which), or a negative error. */
int ffc_project(int nn, const double X[][3], const double p[3], ffc_proj *out);

/* Derivatives of an interior projection with respect to the nodal
 * positions (equivalently displacements) of a slave facet and the master
 * facet.  The slave point is p = sum_a Ns[a] x_a (ns slave nodes with
 * fixed shape values Ns); the master facet is Xm[nm][3] and pr its
 * projection.  Unknowns are ordered [slave node 0 (x,y,z), ..., slave node
 * ns-1, master node 0, ..., master node nm-1]; nd = 3 (ns + nm).
 * Outputs (rows of stride FFC_MAXDOF, first nd entries used):
 *   dxi[2][.]  d xi_a / d u,   dg[.]  d gap / d u,   dn[3][.]  d n_i / d u.
 * Valid for pr->where == FFC_FOOT_INSIDE; FFC_ERR_VALUE otherwise. */
int ffc_project_deriv(int ns, const double Ns[], int nm, const double Xm[][3],
                      const ffc_proj *pr, double dxi[2][FFC_MAXDOF],
                      double dg[FFC_MAXDOF], double dn[3][FFC_MAXDOF]);

/* ------------------------------------------------------------- surfaces */
/* A labelled surface: the boundary faces of a volume mesh that carry one of
 * a set of labels.  Node indices refer to the volume mesh numbering. */

/* Selects the boundary faces whose label is in labs[nlab].
 *   nbe faces, be[nbe*nn] node indices, belab[nbe] labels, beopp[nbe] the
 *   node of the adjacent tetrahedron opposite the face (for orientation),
 *   X[nv*3] node positions.
 * Writes the selected faces, oriented so that the normal points out of
 * the body, into F[cap*nn] and returns their count.
 * Errors: FFC_ERR_LABEL (*bad = the missing label), FFC_ERR_EMPTY,
 * FFC_ERR_INDEX / FFC_ERR_NONFINITE / FFC_ERR_DEGENERATE (*bad = face
 * index), FFC_ERR_CAPACITY (*bad = needed count). */
int ffc_surface_select(int nn, long nbe, const long be[], const long belab[],
                       const long beopp[], long nv, const double X[],
                       int nlab, const long labs[], long cap, long F[],
                       long *bad);

/* Distinct labels among belab[nbe], ascending, into out[cap]; returns the
 * number of distinct labels (may exceed cap: only cap are written). */
long ffc_labels_present(long nbe, const long belab[], long cap, long out[]);

/* Checks a surface F[nf*nn] against nv nodes at positions X[nv*3] + u[nv*3]
 * (u may be NULL): indices in range, finite positions, non-degenerate
 * facets.  On error *bad is the facet index (or node index for
 * FFC_ERR_NONFINITE). */
int ffc_surface_check(int nn, long nf, const long F[], long nv,
                      const double X[], const double u[], long *bad);

/* Area of the surface F[nf*nn] at positions X + u (u may be NULL),
 * integrated with the Gauss rule of the given degree. */
int ffc_surface_area(int nn, long nf, const long F[], long nv,
                     const double X[], const double u[], int degree,
                     double *area);

/* Checks the nt tetrahedra T[nt*4] at positions X + u: FFC_ERR_INVERTED
 * (*bad = the tetrahedron) when one has turned inside out or collapsed
 * (its signed volume, relative to the reference one, below 1e-12), e.g.
 * after a diverged Newton step. */
int ffc_volume_check(long nt, const long T[], long nv, const double X[],
                     const double u[], long *bad);

/* Unit normals N[nf*3] at the centroid of each facet of F[nf*nn], at
 * positions X + u (u may be NULL).  Errors as ffc_surface_check. */
int ffc_surface_normals(int nn, long nf, const long F[], long nv,
                        const double X[], const double u[], double N[],
                        long *bad);

/* --------------------------------------------------------------- search */
/* Contact search: for each quadrature point of each slave facet, the
 * closest point on the master surface (exact: a bounding-volume tree with
 * branch-and-bound), classified as interior, on an edge or vertex shared by
 * master facets (a link with the foot clamped there), or beyond the edge of
 * the master surface (outside the footprint: no link).  A point counts as
 * beyond the edge when its distance past the rim, in the tangent plane of
 * the facet, exceeds edge_tol h_f plus its distance |g| to the facet's
 * plane (the cone over the rim's edge): a point in a symmetry plane, or on
 * a slave surface flush with the master's rim, whose foot on a facet that
 * the deformation tilted falls just past the rim, keeps its link, open or
 * penetrating (the node-to-surface rim rule alike). */

typedef struct {
    double capture_rel;  /* capture distance relative to the partner master
                            facet's longest edge (1); >= 0 */
    double capture_abs;  /* absolute capture distance (length); >= 0.  A point
                            gets a link when its distance to the master
                            surface is <= max(capture_abs, capture_rel h_f) */
    double edge_tol;     /* a foot outside its facet by at most this much in
                            local coordinates still counts as inside (1); >= 0 */
} ffc_search_opts;

/* Defaults: capture_rel 2, capture_abs 0, edge_tol 1e-9. */
ffc_search_opts ffc_search_defaults(void);

/* One contact link: a slave quadrature point and its master partner. */
typedef struct {
    long sf;        /* slave facet (index into the slave facet array) */
    int q;          /* quadrature point index in the slave facet */
    double xs[2];   /* slave local coordinates of the quadrature point (1) */
    long mf;        /* master facet, -1 when the point has no partner */
    double xm[2];   /* master local coordinates of the foot (1) */
    double gap;     /* signed normal gap n . (x_s - x_m) (length) */
    double n[3];    /* unit master normal at the foot (1) */
    int where;      /* FFC_FOOT_* of the foot on the master facet */
    double w;       /* segment links (q = -1, see ffc_mortar_search): the
                       point's weight on the slave facet's reference
                       triangle of area 1/2 (1); unused otherwise (the
                       rule's weight of point q applies) */
} ffc_link;

/* Opaque search structure over one master surface (owns its memory). */
typedef struct ffc_tree ffc_tree;

/* Builds the tree of the master surface F[nf*nn] with node positions
 * x[nv*3] (current configuration).  *out is NULL on error. */
int ffc_tree_build(int nn, long nf, const long F[], long nv, const double x[],
                   ffc_tree **out);

/* Updates the bounding boxes for new node positions x[nv*3] keeping the
 * tree's order (cheaper than a rebuild; queries stay exact, they only get
 * slower if facets moved far relative to each other). */
int ffc_tree_refit(ffc_tree *t, const double x[]);

/* Frees the tree (NULL allowed). */
void ffc_tree_free(ffc_tree *t);

/* Bytes held by the tree. */
long ffc_tree_bytes(const ffc_tree *t);

/* Closest master facet to p within distance rmax: *facet (or -1) and its
 * projection. */
int ffc_tree_nearest(const ffc_tree *t, const double p[3], double rmax,
                     long *facet, ffc_proj *pr);

/* Links of the slave surface Fs[nfs*nns] (positions xs_nodes[*3], usually
 * the same array as the master's) against the tree, Gauss rule of degree
 * qdeg: nfs * ffc_quad_size(qdeg) links, in the order (facet, point).
 * cap is the capacity of links[].  Returns the number of links that have
 * a partner, or an error (FFC_ERR_CAPACITY: cap too small). */
int ffc_search(const ffc_tree *t, int nns, long nfs, const long Fs[],
               long nvs, const double xs_nodes[], int qdeg,
               const ffc_search_opts *o, long cap, ffc_link links[]);

/* The same result from a loop over all master facets (reference for tests
 * and benchmarks). */
int ffc_search_brute(const ffc_tree *t, int nns, long nfs, const long Fs[],
                     long nvs, const double xs_nodes[], int qdeg,
                     const ffc_search_opts *o, long cap, ffc_link links[]);

/* Links of np points p[np*3] (e.g. slave nodes) against the tree, with
 * the footprint and capture rules of ffc_search; links[k].sf = k, q = 0.
 * Returns the number of points with a partner, or an error. */
int ffc_search_points(const ffc_tree *t, long np, const double p[],
                      const ffc_search_opts *o, ffc_link links[]);

/* --------------------------------------------------- mortar segments */
/* Segment-to-segment integration (mortar): each slave facet is clipped
 * against the projections of the master facets it overlaps, and the
 * contact integrals are evaluated with a Gauss rule on each piece, so
 * that integrands that are smooth on each piece but kink at master edges
 * are integrated exactly (the contact patch test).  Linear facets. */
#define FFC_CLIPMAX 8   /* vertices of an input polygon of ffc_clip_polygon */

/* Intersection of the convex counter-clockwise polygons a[na] and b[nb]
 * (3 <= na, nb <= FFC_CLIPMAX) into out[cap] (cap >= na + nb),
 * counter-clockwise.  Returns its vertex count (0: they do not overlap,
 * or only along an edge or at a point), or FFC_ERR_NULL, _SIZE,
 * _CAPACITY, _NONFINITE, _DEGENERATE (an input that is not
 * counter-clockwise with a positive area). */
int ffc_clip_polygon(int na, const double a[][2], int nb, const double b[][2], int cap, double out[][2]);

/* The integration points of the slave facet Xs[3][3] (vertex positions)
 * over the part covered by the master facet Xm[3][3] projected along the
 * slave normal: xi[cap][2] local coordinates on the slave facet, w[cap]
 * weights on its reference triangle (area 1/2), the Gauss rule of degree
 * qdeg on each triangle of the clipped polygon; *covered = the covered
 * area in local coordinates (1/2: all).  With exi != NULL also the points
 * of the segment's moving edges (those on a projected master edge):
 * exi[ecap][2], and edv[ecap][18] their weight times the outward normal
 * velocity of the edge per unit change of each dof (slave facet nodes,
 * then master facet nodes; x, y, z each), *ne their count: the boundary
 * term of the segment's motion (see ffc_mortar.c).  Returns the number of
 * points (0: no overlap), FFC_ERR_CAPACITY when cap or ecap is too small,
 * or an error. */
int ffc_mortar_segment(int qdeg, const double Xs[3][3], const double Xm[3][3], long cap, double xi[][2],
                       double w[], long ecap, double exi[][2], double edv[][18], long *ne, double *covered);

/* A moving-edge point of a segment: where the segment's boundary follows
 * a master edge, the boundary term of its motion in the tangent. */
typedef struct {
    long sf, mf;       /* slave facet, master facet */
    double xs[2];      /* slave local coordinates of the point (1) */
    double dv[FFC_MAXDOF]; /* line weight x outward normal velocity per unit change of each dof of
                          the slave facet's nn nodes then the master facet's nn, x, y, z each, as a
                          link's dofs (1/length; the first 3 nodes' entries only: a segment
                          follows the vertex triangles) */
} ffc_mortar_edge;

/* Dual (biorthogonal) multiplier basis of a linear slave facet from the
 * points xi[n], w[n] of its covered part: Phi_a = sum_b A[a][b] N_b with
 * sum_q w_q Phi_a N_b = delta_ab sum_q w_q N_a (see ffc_mortar.c).  A = I
 * (standard basis) for n = 0 or a nearly singular coverage. */
int ffc_dual_basis(long n, const double xi[][2], const double w[], double A[3][3]);

/* Segment links of the slave surface Fs[nfs*nn] (positions x[nvs*3])
 * against the tree's master surface (nn = the tree's nodes per facet, 3
 * or 6; the segments of 6-node facets are those of their vertex
 * triangles, see ffc_mortar_links): for every slave
 * facet, every master facet that faces it (normals opposed) and whose box
 * overlaps the slave facet's box grown by the capture distance of
 * ffc_search gives the points of ffc_mortar_segment, provided one of them
 * lies within that distance at its segment's centre (a facet is in the
 * band or not, never cut by its edge); each link has q = -1, its weight w, the
 * master facet and the foot of the point on the facet's plane.  Links of
 * a facet are consecutive, facets in order.  Returns the number of links
 * written; FFC_ERR_CAPACITY with *need the count when cap is too small. */
int ffc_mortar_search(const ffc_tree *t, long nfs, const long Fs[], long nvs, const double x[], int qdeg,
                      const ffc_search_opts *o, long cap, ffc_link links[], long *need);

/* The facet pairs of ffc_mortar_search (slave facets Fs[nfs*nn], nn the
 * tree's nodes per facet): pairs[2 k] the slave facet,
 * pairs[2 k + 1] the master facet of pair k (cap pairs at most; *need the
 * count).  Returns the count or an error (FFC_ERR_CAPACITY). */
int ffc_mortar_pairs(const ffc_tree *t, long nfs, const long Fs[], long nvs, const double x[],
                     const ffc_search_opts *o, long cap, long pairs[], long *need);

/* The segments of given facet pairs at positions x[nvs*3] (slave facets
 * Fs[nfs*nn], master facets Fm[nfm*nn], nn = 3 or 6 nodes each): their
 * links (as ffc_mortar_search,
 * whatever the capture distance: the pairs were chosen by it) into
 * links[lcap] (*lneed their count) and, with edges != NULL, their
 * moving-edge points into edges[ecap] (*eneed).  Returns the link count,
 * FFC_ERR_CAPACITY (the needs set) or an error (*lneed = the pair at
 * fault for FFC_ERR_INDEX).  6-node facets: the segments are clipped on
 * the vertex triangles (exact for straight-sided facets, the curved
 * facet's edges to O(h^2 / R) otherwise), each point xi lies on the
 * curved slave facet x(xi) = sum_a N_a(xi) x_a and its foot on the curved
 * master facet; the edge points' velocities have the vertices' dofs only. */
int ffc_mortar_links(int nn, long nfs, const long Fs[], long nfm, const long Fm[], long nvs, const double x[], int qdeg,
                     long npairs, const long pairs[], long lcap, ffc_link links[], long *lneed, long ecap,
                     ffc_mortar_edge edges[], long *eneed);

/* ------------------------------------------------ normal contact links */
/* Augmented-Lagrangian normal contact (after Laursen; the seed's
 * ContactLink3D).  Sign convention: gap g = n2 . (x1 - x2) >= 0 when open;
 * contact pressure t_N = <lambda_N - eps_N g> (Macaulay bracket), >= 0.
 * The seed writes g_seed = -g, t_N = <lambda_N + eps_N g_seed>: the same. */

/* State of one link after an evaluation. */
typedef struct {
    double x[3];       /* slave point, current configuration (length) */
    double xi[2];      /* master foot on the facet's extension (1) */
    double n[3];       /* unit master normal at the foot (1) */
    double gap;        /* g (length) */
    double tn;         /* contact pressure t_N (force/length^2) */
    double da;         /* w * area element: the point's area (length^2) */
    int active;        /* 1 when lambda_N - eps_N g > 0 */
    double slip[3];    /* friction: relative motion r of the slave point over
                          the master since the last converged step (length) */
    double t[3];       /* friction: tangential traction T resisting the slip;
                          the slave is pushed by -T (force/length^2) */
    int fstate;        /* friction: FFC_FRIC_OPEN, _STICK or _SLIP */
} ffc_link_state;

/* Residual and tangent of one link: slave facet Xs[ns][3] (current
 * positions), its reference positions Xs0[ns][3] (area element when
 * effects->finite_def == 0), slave point xs with quadrature weight w,
 * master facet Xm[nm][3] (current); multiplier lambda (force/length^2),
 * penalty eps (force/length^3, > 0).  Unknowns: [slave nodes, master
 * nodes] x (x, y, z), nd = 3 (ns + nm).
 * Outputs: st; R[nd] the contribution to the internal-force residual;
 * K[nd][nd] (row stride FFC_MAXDOF) its derivative, or K == NULL for the
 * residual only.  An inactive link gives R = 0, K = 0. */
int ffc_link_normal(const ffc_effects *effects, int ns, const double Xs[][3],
                    const double Xs0[][3], const double xs[2], double w,
                    int nm, const double Xm[][3], double lambda, double eps,
                    ffc_link_state *st, double R[FFC_MAXDOF],
                    double K[FFC_MAXDOF][FFC_MAXDOF]);

/* The nodes of one contact pair: slave and master facets into a common
 * node numbering; node i has reference position X[3i..3i+2] and
 * displacement u[3i..3i+2]; its degrees of freedom are 3i, 3i+1, 3i+2. */
typedef struct {
    int ns;            /* nodes per slave facet (3 or 6) */
    long nfs;          /* slave facets */
    const long *Fs;    /* [nfs*ns] slave facet nodes */
    int nm;            /* nodes per master facet (3 or 6) */
    long nfm;          /* master facets */
    const long *Fm;    /* [nfm*nm] master facet nodes */
    long nv;           /* nodes */
    const double *X;   /* [nv*3] reference positions (length) */
    const double *u;   /* [nv*3] displacements (length) */
    const double *u_prev; /* [nv*3] displacements at the last converged step
                          (length); read only when friction is on in a
                          quasi-static scene */
    const double *v;   /* [nv*3] velocities at the end of the step (length/time);
                          read only when friction is on in a dynamic scene
                          (effects->dynamic), in place of u_prev */
} ffc_pair;

/* The contact law and where its multipliers live. */
typedef struct {
    double eps_n;      /* penalty (force/length^3), > 0 */
    int nodal;         /* 1: one multiplier per slave node, lambda[nv]; the
                          pressure at a point uses the interpolated
                          multiplier, and the Uzawa update drives the
                          weighted nodal gap  int N_a g dA / int N_a dA  to
                          zero (one constraint per node: well posed).
                          0: one multiplier per slave quadrature point,
                          lambda[nl], updated pointwise as in the seed (more
                          constraints than contact unknowns: the multipliers
                          may drift and Uzawa may stall) */
    int material_only; /* 1: tangent without the geometric terms (variation of
                          the normal, the foot and the area): positive
                          semi-definite, for a descent direction when the
                          consistent tangent is indefinite; 0: consistent;
                          2: the material tangent in ranked form
                          (FFC_TANGENT_RANKED; the nodal law only) */
    double mu;         /* Coulomb coefficient (1), >= 0; read only when
                          effects->friction (mu = 0 then skips all friction work) */
    double eps_t;      /* tangential penalty, > 0 when friction: force/length^3
                          (quasi-static: T_tr = lambda_T + eps_t r), or
                          force*time/length^3 (dynamic: T_tr = lambda_T + eps_t v_rel) */
    double dt;         /* time step (time), > 0 when friction is on in a dynamic
                          scene: the slip reported over the step is dt v_rel */
    double dvdu;       /* dynamic friction: the time integrator's d v / d u at the
                          end of the step (1/time, e.g. gamma / (beta dt) for
                          Newmark), >= 0.  The tangent is K + dvdu D with
                          D = dR/dv the damping matrix; 0 gives K alone */
    const double *fixed; /* [3*nv] or NULL: nonzero where a node's dof is
                          prescribed (Dirichlet): > 0 held at zero (as on a
                          symmetry plane), < 0 moved.  Nodal friction drops a
                          direction e_k held at zero of a slave node that lies
                          in the contact plane (|n~_k| < 0.9, as node-to-surface
                          does): the k components of the node's weighted slip
                          and weighted normal are zeroed before its return
                          map (on a symmetry plane the mirror half's
                          contributions cancel them).  A moved direction (a
                          face pushed along the contact plane) keeps its
                          friction, which the support's reaction carries */
    const double *dual; /* [9 nfs] or NULL: nodal law with dual multipliers (on
                          6-node facets too: N_b the vertex triangle's linear
                          shape functions), Phi_a = sum_b A_ab N_b on slave facet f
                          with A = dual + 9 f (row-major, ffc_dual_basis) in place
                          of N_a, in the weighted gap, the pressure and the
                          friction sums alike; NULL: standard N_a */
    long nedge;        /* segment links (qdeg 0): the moving-edge points of their segments,
                          edge[nedge] (ffc_mortar_links), whose motion enters the tangent;
                          0: the tangent at fixed segments */
    const ffc_mortar_edge *edge;
    int tdual;         /* 1: the nodal law's friction sums (the weighted slip and
                          normal, the point traction) use the dual basis of a full
                          linear facet, Phi_a = 4 N_a - 1, so that a node's weighted
                          slip is its own, not an average with its neighbours';
                          needs dual NULL, nedge 0 and linear slave facets (else
                          ignored); the weighted gap and the pressure keep N_a.
                          0: the friction sums use the normal part's shape values */
    const unsigned char *lsel; /* [nl] or NULL (every link): the nodal law's residual,
                          statistics and ranked tangent (FFC_TANGENT_NONE or
                          FFC_TANGENT_RANKED; not with dual, nedge or another
                          tangent: FFC_ERR_VALUE) from the links k with lsel[k]
                          != 0 only, a share of them: the shares' sums are the
                          whole's, with nsum completing the node sums */
    int (*nsum)(void *ctx, int st, long n, double buf[]);
                       /* with lsel: called once per assembly, on every path, with
                          this share's status st and its partial node sums buf[n]
                          (8 per node of the linked links' slave facets, ascending
                          node index:
                          G_a, W_a, the weighted slip's and normal's sums); it
                          replaces buf by the sums over every share and returns
                          their combined status (FFC_OK only when every share's
                          st is; buf may be NULL when st is not FFC_OK) */
    void *nsum_ctx;    /* nsum's first argument */
} ffc_law;

/* ------------------------------------------------------ Coulomb friction */
/* Formulation.  Two forms of the same law, chosen by effects->dynamic.
 * Quasi-static (incremental): the slip r is the relative motion of the
 * slave point over the master material point under it since the last
 * converged step,
 *     r = sum_a N1_a (x_a - x_a^n) - sum_b N2_b(xi) (x_b - x_b^n).
 * Dynamic (the seed's velocity form): the relative velocity
 *     r = v_rel = sum_a N1_a v_a - sum_b N2_b(xi) v_b
 * takes its place, with eps_T in force*time/length^3.  With the
 * tangential multiplier lambda_T (a 3-vector in the tangent plane), the
 * trial traction is
 *     T_tr = P (lambda_T + eps_T r),   P = I - n n^T,
 * whose Euclidean norm equals the metric norm sqrt(t_a m^ab t_b) of its
 * covariant components.  Return map: stick when |T_tr| < mu t_N (T =
 * T_tr), slip otherwise (T = mu t_N T_tr / |T_tr|), with the current
 * t_N so that the slip bound is linearized with it.  T resists the slip:
 * the slave is pushed by -T, the master by +T.
 * The two forms agree when the velocity is the backward difference
 * v = (x - x^n) / dt and eps_T(dynamic) = eps_T(quasi-static) dt.  In the
 * velocity form the derivative of the residual splits into a stiffness
 * K = dR/du at fixed velocities (the foot slides, the normal turns) and
 * the damping matrix D = dR/dv; with the integrator's v(u) the tangent
 * is K + (dv/du) D (law->dvdu). */
enum { FFC_FRIC_OPEN = 0, FFC_FRIC_STICK = 1, FFC_FRIC_SLIP = 2 };

/* Result of the return map at one point. */
typedef struct {
    double t[3];        /* traction T (force/length^2) */
    double dt_dr[3][3]; /* dT/dr (force/length^3) */
    double dt_dn[3][3]; /* dT/dn (force/length^2) */
    double dt_dtn[3];   /* dT/dt_N (1) */
    int state;          /* FFC_FRIC_* (OPEN when t_N <= 0: T = 0) */
} ffc_fric;

/* Return map at one point: unit normal n[3], multiplier lam_t[3], slip
 * r[3], mu >= 0, eps_t > 0, pressure tn.  No division by zero: t_N = 0
 * gives OPEN, and |T_tr| = 0 with mu t_N = 0 gives T = 0.
 * FFC_ERR_NULL, FFC_ERR_VALUE (mu, eps_t), FFC_ERR_NONFINITE. */
int ffc_friction_map(const double n[3], const double lam_t[3], const double r[3],
                     double mu, double eps_t, double tn, ffc_fric *out);

/* Residual and tangent of one link with the law's friction: as
 * ffc_link_normal with, when effects->friction and law->mu > 0, the
 * motion of the nodes Ds[ns][3], Dm[nm][3] (quasi-static: x - x^n since
 * the last converged step; dynamic: the velocities) and the multiplier
 * lam_t[3].  Friction residual da S^T T with S = dr/dD at fixed foot;
 * its tangent includes the slip of the foot, the turning of the normal
 * and the pressure's variation (non-symmetric); dynamic: K + law->dvdu D.
 * st->slip is r (quasi-static) or law->dt r (dynamic). */
int ffc_link_contact(const ffc_effects *effects, int ns, const double Xs[][3],
                     const double Xs0[][3], const double Ds[][3], const double xs[2],
                     double w, int nm, const double Xm[][3], const double Dm[][3],
                     double lambda, const double lam_t[3], const ffc_law *law,
                     ffc_link_state *st, double R[FFC_MAXDOF],
                     double K[FFC_MAXDOF][FFC_MAXDOF]);

/* Summary of an assembly or augmentation. */
typedef struct {
    long linked;       /* links with a master partner */
    long active;       /* links with t_N > 0 */
    double max_pen;    /* largest penetration max(0, -g) over linked points (length) */
    double max_pen_node; /* largest weighted nodal penetration (nodal law, augmentation) */
    double max_dlam;   /* largest |lambda_new - lambda| (augmentation only) */
    double max_tn;     /* largest contact pressure */
    double force[3];   /* total normal contact force on the slave side (force) */
    long stick, slip;  /* friction: sticking, sliding links (pointwise law) or
                          slave nodes (nodal law) */
    double max_dlam_t; /* friction: largest |lambda_T,new - lambda_T| (augmentation) */
    double max_tt;     /* friction: largest tangential traction |T| */
    double force_t[3]; /* friction: total friction force on the slave side (force) */
    double dissipation; /* friction: sum over points of da T . r, the work
                          dissipated by slip since the last converged step (force*length) */
    double max_slip;   /* friction: largest tangential slip |r_T| of a pressed point (pointwise
                          law) or slave node (nodal law, weighted slip) since the last converged
                          step (length; dynamic: dt |v_rel,T|) */
} ffc_stats;

/* Adds the contact residual of all links into R[3nv] and writes the
 * tangent as triplets (Ti, Tj, Tv)[cap] (NULL: residual only).  lambda:
 * [nv] per node or [nl] per link, as law->nodal says; lam_t the
 * tangential multipliers, 3 per node [nv*3] or per link [nl*3] likewise
 * (read only with friction on and law->mu > 0, NULL allowed otherwise;
 * the tangent is then non-symmetric).  The nodal law applies the return
 * map at the nodes to the weighted slip (see ffc_nodal.c).
 * *ntrip is the number of triplets written, or the number needed when
 * FFC_ERR_CAPACITY is returned (R is then incomplete).
 * On error *bad is the link at fault. */
int ffc_assemble(const ffc_effects *effects, const ffc_pair *pair, int qdeg,
                 long nl, const ffc_link links[], const double lambda[],
                 const double lam_t[], const ffc_law *law, double R[], long cap, long Ti[], long Tj[],
                 double Tv[], long *ntrip, ffc_stats *stats, long *bad);

/* Uzawa update: pointwise lambda_q <- <lambda_q - eps g_q> (0 without a
 * partner), or nodal lambda_a <- <lambda_a - eps g_a> with the weighted
 * gap g_a = sum_q N_a da g / sum_q N_a da over linked points (0 at slave
 * nodes without linked points; the entries of nodes that are not slave
 * nodes of this pair are left as they are, so pairs may share lambda);
 * stats->max_dlam measures the change.  With
 * friction, lam_t <- T of each node or link (0 where t_N = 0), evaluated
 * with the pressures before the normal update; stats->max_dlam_t. */
int ffc_augment(const ffc_effects *effects, const ffc_pair *pair, int qdeg,
                long nl, const ffc_link links[], double lambda[], double lam_t[],
                const ffc_law *law, ffc_stats *stats, long *bad);

/* Per-link output P[nl*FFC_POINT_COLS]: x, y, z (current slave point),
 * gap, t_N, active, area da, master facet; with friction (zeros without)
 * the traction on the slave -T (x, y, z), the friction state FFC_FRIC_*,
 * and the dissipation density T . r (force/length). */
#define FFC_POINT_COLS 13
int ffc_points(const ffc_effects *effects, const ffc_pair *pair, int qdeg,
               long nl, const ffc_link links[], const double lambda[],
               const double lam_t[], const ffc_law *law, double P[], long *bad);

/* The same columns per slave node of the nodal law (ascending node index,
 * every vertex of a slave facet: the multipliers' nodes, also of 6-node
 * facets): current position, weighted gap (NaN
 * without weight), nodal pressure t_a, active (t_a > 0), the node's
 * weight W_a = sum_q N_a da (its tributary area), the master facet of its
 * first link (-1: none); with friction the nodal traction on the slave
 * -T_a, its state and T_a . r~_a (the weighted slip).  *n the rows
 * (needed, with FFC_ERR_CAPACITY when cap is smaller); FFC_ERR_VALUE for
 * the pointwise law.  Mortar scenes report these (the dual multipliers'
 * pointwise values are no pressures). */
int ffc_points_nodes(const ffc_effects *effects, const ffc_pair *pair, int qdeg, long nl, const ffc_link links[],
                     const double lambda[], const double lam_t[], const ffc_law *law, long cap, double P[], long *n,
                     long *bad);

/* Writes the rows of ffc_points (n points) as a legacy-VTK point cloud
 * with scalar fields gap, pressure, active; FFC_ERR_VALUE if the file
 * cannot be written. */
int ffc_points_vtk(const char *path, long n, const double P[]);

/* Writes the rows k of the column-major table A[ncol*n] (column j holds
 * A[j*n .. j*n + n-1]) whose mask[k] is non-zero (mask NULL: all rows) as
 * whitespace-separated text, after a header line "# " + header;
 * FFC_ERR_VALUE if the file cannot be written. */
int ffc_write_columns(const char *path, const char *header, long n, int ncol,
                      const double A[], const double mask[]);

/* ------------------------------------------------------------ line search */
/* The line search of every Newton loop (the condensed Newton here, the
 * scene driver's Newton in the script), by reverse communication: the
 * caller evaluates where it is told and reports.
 *
 * Formulation: along a direction d from u, g(a) = r(u + a d) . d (g(0) <
 * 0 for a descent direction).  Phase 1 (secant): the root of g on [0, a0]
 * by regula falsi (Illinois: a bound kept twice has its g halved), the
 * next point clamped to 5 % inside the bracket; a point is taken once
 * |g| <= ls_tol |g(0)|, or where g < 0 at the upper bound, or at a = 1
 * when the caller reports the full step taken (|r| at least halved with
 * the contact state unchanged: a tangent that is not symmetric can make
 * g(0) small against |r| |d|).  Phase 2 (guard): a step that makes |r|
 * more than ten times |r(u)| is halved.  Each phase takes at most max_ls
 * evaluations; a point the caller rejects (an inverted element) shortens
 * the step (phase 1: to the middle of the bracket, as its new upper
 * bound; phase 2: halved) and counts as an evaluation.  The point last
 * evaluated is not evaluated again. */
typedef struct {
    int max_ls;        /* evaluations per phase (>= 0) */
    double ls_tol;     /* phase 1's acceptance |g| <= ls_tol |g(0)| (0 < ls_tol < 1) */
    double g0, rn;     /* g(0) and |r(u)| */
    double a;          /* the point to evaluate, or the step taken at the end */
    double at;         /* the point last evaluated (-1: none) */
    double rt;         /* |r| there */
    double alo, glo, ahi, ghi; /* phase 1's bracket and g at its ends */
    int side;          /* the bound phase 1 moved last: -1 the lower, 1 the upper, 0 none */
    int phase;         /* 1 secant, 2 guard, 0 done */
    int guard;         /* 1: phase 2 follows phase 1 */
    int it;            /* evaluations in the present phase (count) */
    int waiting;       /* 1: a point was handed out and not yet reported */
    long cuts;         /* steps shortened (count) */
} ffc_linesearch;

/* Starts a search from a0 (the largest admissible step, <= 1) with g(0)
 * and |r(u)|; secant / guard: run phase 1 / phase 2.  FFC_ERR_VALUE for
 * max_ls < 0 or ls_tol outside (0, 1). */
int ffc_ls_start(ffc_linesearch *s, int max_ls, double ls_tol, double a0, double g0, double rn, int secant,
                 int guard);
/* 1: evaluate at *a, then ffc_ls_report (or ffc_ls_reject); 0: the search
 * is over, take the step *a. */
int ffc_ls_next(ffc_linesearch *s, double *a);
/* The evaluation at the point handed out: g there, |r| there, and (at
 * a = 1) whether the full step is taken on |r| alone. */
int ffc_ls_report(ffc_linesearch *s, double g, double rnorm, int full_taken);
/* The point handed out is not admissible (not evaluated). */
int ffc_ls_reject(ffc_linesearch *s);

/* ----------------------------------------------------------------- scenes */
/* A contact scene: the nodes of one mesh (reference positions, and the
 * tetrahedra for the inversion check) and any number of contact pairs.
 * Each pair owns its slave and master facets, its search tree (built at
 * the first search, refitted at the next ones), its links, its
 * multipliers (never touched by another pair), their checkpoint at the
 * last commit, and its statistics.  The scene owns its memory; nothing is
 * global.  A pair with mu = 0 computes no friction term; the scene's
 * dynamic and finite_def effects apply to every pair. */
typedef struct ffc_scene ffc_scene;

enum {
    FFC_METHOD_AL = 0,          /* surface-to-surface augmented Lagrangian */
    FFC_METHOD_NTS = 1,         /* node-to-surface Lagrange multipliers (linear facets; see ffc_nts_*) */
    FFC_METHOD_MORTAR = 2       /* segment-to-segment augmented Lagrangian: the nodal law on the
                                   segment links (linear or 6-node facets, the multipliers at the
                                   vertices; qdeg is the rule on each segment triangle).
                                   ffc_scene_search chooses the facet pairs
                                   (ffc_mortar_pairs); every assembly and augmentation clips
                                   them again at its u (ffc_mortar_links), and the consistent
                                   tangent has the segments' motion (ffc_law.edge);
                                   ffc_scene_points reports the segments of the last of those */
};
enum {
    FFC_TANGENT_NONE = 0,       /* residual only */
    FFC_TANGENT_CONSISTENT = 1, /* exact derivative of the residual */
    FFC_TANGENT_MATERIAL = 2,   /* without the geometric terms (see ffc_law.material_only) */
    FFC_TANGENT_RANKED = 3      /* the material tangent of the nodal law as a sum of low-rank terms,
                                   one to four per slave node: K = sum_k U_k V_k^T, written as
                                   triplets (dof, 2 k, U_k[dof]) and (dof, 2 k + 1, V_k[dof]); the
                                   condensed Newton then solves a system of the terms' count
                                   (Woodbury) instead of one of the tangent's support */
};

/* A pair's method, law and search options. */
typedef struct {
    int method;        /* FFC_METHOD_* */
    int qdeg;          /* quadrature degree on slave facets (1..6) */
    int nodal;         /* 1: multipliers at slave nodes, 0: at quadrature points */
    double mu;         /* Coulomb coefficient (1), >= 0; 0: frictionless */
    double eps_n;      /* normal penalty (force/length^3), > 0; 0: not set yet (assembly and
                          augmentation refuse the scene until it is: ffc_scene_auto_penalty) */
    double eps_t;      /* tangential penalty (force/length^3; dynamic: force*time/length^3),
                          >= 0; 0: eps_n (dynamic: eps_n / dvdu, the same stiffness against the step's slip) */
    ffc_search_opts search; /* capture distances and edge tolerance */
    /* node-to-surface pairs (FFC_METHOD_NTS; the law's nu_s is mu) */
    double mu_d;       /* dynamic coefficient (1), 0 <= mu_d <= mu; < 0: mu */
    double gtol;       /* gap tolerance (length), >= 0; 0: 1e-11 x the pair's facet size */
    double ftol;       /* tension release below -ftol x the largest normal force (1), >= 0 */
    int max_flips;     /* state changes of a node per step before the chattering guard (>= 1) */
    double scale;      /* row scale (force/length), >= 0; 0: the mean free diagonal of the
                          scene's bulk matrix (ffc_scene_set_bulk) */
    /* mortar pairs (FFC_METHOD_MORTAR) */
    int dual;          /* 1: dual (biorthogonal) multipliers at the slave nodes, 0: standard */
    /* augmented Lagrangian pairs with the nodal law on linear facets */
    int dual_t;        /* 1: the friction sums in the dual basis (ffc_law.tdual), 0: in N_a;
                          1 elsewhere (another method, nodal 0, quadratic facets): FFC_ERR_VALUE
                          (FFC_ERR_NODES for quadratic facets) */
} ffc_pair_opts;

/* Defaults: augmented Lagrangian, qdeg 4, nodal, mu 0, eps_n 0 (must be
 * set), eps_t 0, ffc_search_defaults(); node-to-surface: mu_d -1 (mu),
 * gtol 0 (automatic), ftol 1e-9, max_flips 4, scale 0 (from the bulk);
 * mortar: dual 1; dual_t 0.  A mortar pair needs nodal = 1. */
ffc_pair_opts ffc_pair_defaults(void);

/* FFC_OK, or FFC_ERR_VALUE / FFC_ERR_QUAD for an option out of range. */
int ffc_pair_opts_check(const ffc_pair_opts *o);

/* A scene over nv nodes at reference positions X[nv*3], facets of nper
 * nodes (3 or 6), nt tetrahedra T[nt*4] (corner nodes; nt = 0: no
 * inversion check).  *out is NULL on error. */
int ffc_scene_create(int nper, long nv, const double X[], long nt, const long T[],
                     const ffc_effects *effects, ffc_scene **out);
void ffc_scene_free(ffc_scene *s);
/* The scene's driver settings (see "driver settings"; never NULL for a
 * scene): the script's driver reads and the user sets them by name. */
ffc_settings *ffc_scene_settings(ffc_scene *s);
/* The line search of the script driver's Newton loop, held by the scene
 * (ffc_ls_*, its settings maxLineSearch and lsTol). */
ffc_linesearch *ffc_scene_line_search(ffc_scene *s);

/* What the scene's bulk operator is: its law and what the law declares,
 * from which the driver chooses the solver path (a linear symmetric bulk:
 * factorized once, the contact condensed; otherwise the whole tangent at
 * every Newton iteration) and the contact kernels their geometry. */
typedef enum {
    FFC_BULK_LINEAR = 0,      /* linear elasticity (small strain) */
    FFC_BULK_NEOHOOKEAN = 1,  /* compressible Neo-Hookean (finite deformation, total Lagrangian) */
    FFC_BULK_USER = 2         /* the scene's own residual and tangent */
} ffc_bulk_kind;
typedef struct {
    ffc_bulk_kind kind;
    int linear;        /* 1: the internal force is linear in u (its tangent constant) */
    int symmetric;     /* 1: the tangent is symmetric */
    int finite;        /* 1: finite deformation: contact geometry in the current configuration
                          (ffc_effects.finite_def) */
} ffc_bulk_law;
/* what a built-in law declares (FFC_BULK_USER: nonlinear, symmetric, small strain, until the scene says) */
ffc_bulk_law ffc_bulk_law_of(ffc_bulk_kind kind);
/* Sets the scene's bulk law (and its effects' finite_def).  FFC_ERR_VALUE
 * for an unknown kind, a flag other than 0 or 1, a linear finite law, or a
 * built-in law declared otherwise than it is. */
int ffc_scene_set_law(ffc_scene *s, const ffc_bulk_law *law);
int ffc_scene_law(const ffc_scene *s, ffc_bulk_law *law);
int ffc_scene_npairs(const ffc_scene *s);
int ffc_scene_effects(const ffc_scene *s, ffc_effects *fx);

/* Adds the pair of slave facets Fs[nfs*nper] and master facets
 * Fm[nfm*nper] (node indices; outward orientation) with options o;
 * returns its index (>= 0) or an error (FFC_ERR_INDEX: *bad = the facet
 * entry at fault; FFC_ERR_FUSED: *bad = a slave facet whose vertices are
 * all master nodes, the bodies being meshed as one; FFC_ERR_INTERIOR: *bad
 * = a facet that two of the scene's tetrahedra share, so that the bodies
 * on its two sides are one mesh there: a slave facet f as f, a master
 * facet f as nfs + f). */
int ffc_scene_add_pair(ffc_scene *s, long nfs, const long Fs[], long nfm, const long Fm[],
                       const ffc_pair_opts *o, long *bad);

/* Options of pair k, and their change (a new qdeg or nodal setting
 * resets that pair's links and multipliers). */
int ffc_scene_pair_opts(const ffc_scene *s, int k, ffc_pair_opts *o);
int ffc_scene_set_pair_opts(ffc_scene *s, int k, const ffc_pair_opts *o);

/* Dynamic scenes: the velocities v[nv*3] at the end of the step, the
 * step dt and the integrator's dv/du, read by the friction terms. */
int ffc_scene_set_motion(ffc_scene *s, const double v[], double dt, double dvdu);

/* The prescribed dofs of the scene's nodes: fixed[nv*3] nonzero where a
 * dof is prescribed (Dirichlet), > 0 where it is held at zero (a symmetry
 * plane's), < 0 where it is moved; copied; NULL clears them.  Read by the
 * nodal friction law (ffc_law.fixed: a direction held at zero in a slave
 * node's contact plane is dropped from its return map) and by the free
 * rigid motions (ffc_scene_free_motions: any nonzero entry). */
int ffc_scene_set_fixed(ffc_scene *s, const double fixed[]);

/* Contact search of every pair at x = X + u[nv*3]; *linked (may be NULL)
 * the number of linked points.  On error *bad is the pair (or the node
 * with a non-finite position). */
int ffc_scene_search(ffc_scene *s, const double u[], long *linked, long *bad);

/* Adds the contact residual of every pair at u into R[nv*3] and, unless
 * tangent is FFC_TANGENT_NONE, writes the tangent as triplets (Ti, Tj,
 * Tv)[cap]; *ntrip the triplets written, or needed with FFC_ERR_CAPACITY
 * (R is then incomplete: call again with room).  FFC_TANGENT_RANKED
 * numbers the terms over all pairs (a pair's after the pairs before it);
 * FFC_ERR_VALUE (*bad = the pair) for an augmented Lagrangian pair with
 * multipliers at quadrature points. */
int ffc_scene_assemble(ffc_scene *s, const double u[], int tangent, double R[], long cap, long Ti[], long Tj[],
                       double Tv[], long *ntrip, long *bad);

/* Uzawa update of every pair's multipliers at u (see ffc_augment). */
int ffc_scene_augment(ffc_scene *s, const double u[], long *bad);

/* A converged step: u becomes the friction history and the multipliers
 * are checkpointed.  restore: back to the checkpoint (a step cut).
 * reset: zero history, velocities, multipliers, links. */
int ffc_scene_commit(ffc_scene *s, const double u[]);
int ffc_scene_restore(ffc_scene *s);
int ffc_scene_reset(ffc_scene *s);

/* Node-to-surface pairs (FFC_METHOD_NTS; a scene's pairs all use one
 * method).  Each such pair keeps the table of its slave nodes
 * (ffc_nts_node: state, partner facet, force), checkpointed by commit and
 * restored by restore like the multipliers of the other method; search,
 * assembly and augmentation pass over it.  In a step: ffc_scene_nts_step
 * (a new step: per-step flips, kept facets and forces cleared), then
 * repeat: ffc_scene_nts_rows (locate the nodes at u, the constraint rows
 * of every pair stacked: see ffc_nts_rows; rows of pair k follow those of
 * pairs < k, and a C-block column Bj >= 3 nv is shifted likewise), the
 * saddle-point solve, ffc_scene_nts_update (locate again, forces from the
 * multipliers m[nrows], transitions; *changes in all pairs), until no
 * node changes, the gaps close and Coulomb's law holds (statistics
 * "changes", "gapErr", "slideRes").  The node-to-surface law of a pair
 * takes nu_s = mu, and mu_d, gtol, ftol, max_flips, scale from its
 * options.  FFC_ERR_VALUE without a row scale (no option, no bulk);
 * FFC_ERR_CAPACITY with the sizes needed in *ntrip, *nrows. */
int ffc_scene_nts_step(ffc_scene *s);
int ffc_scene_nts_rows(ffc_scene *s, const double u[], const double fixed[], long cap, long Bi[], long Bj[],
                       double Bv[], double Fv[], long ccap, double c[], long *ntrip, long *nrows, long *bad);

/* The saddle-point solve of a node-to-surface step on the factored bulk
 * (ffc_scene_set_bulk): the rows at u (ffc_scene_nts_rows with fixed[n])
 * and [K Bf'; B Cm] [x; m] = [rhs; c] solved for x[n] and the
 * multipliers m[*nrows] (mcap: capacity of m).
 *
 * Formulation: with K factored once, x0 = K^-1 rhs (Dirichlet values
 * lifted as in ffc_scene_solve) and G the compliance of the free dofs C
 * the rows touch (columns kept with the other solves'), x = x0 - K^-1
 * Bf' m and the rows give the Schur complement system
 *     (Cm - B_C G Bf_C') m = c - B x0        (nr x nr, dense LU),
 * then x by one back-solve.  When K is singular and shifted (K + S, see
 * ffc_scene_solve), K^-1 does not exist: y = x_C and m solve the coupled
 *     [I - G S_C, G Bf_C'; B_C, Cm] [y; m] = [x0_C; c]
 * (order |C| + nr) and x = x0 + (K + S)^-1 (S_C y - Bf' m).  Up to two
 * steps of iterative refinement on the whole system's residual.
 * FFC_ERR_EMPTY without a bulk, FFC_ERR_CAPACITY when m is too small
 * (*nrows = the count needed) or C would hold more than the bulk's mmax
 * dofs (*bad = their count), FFC_ERR_SINGULAR when the system cannot be
 * factorized or its residual stays above 1e-6 relative; the errors of
 * ffc_scene_nts_rows. */
int ffc_scene_nts_solve(ffc_scene *s, const double u[], const double fixed[], const double rhs[], double x[],
                        long mcap, double m[], long *nrows, long *bad);
int ffc_scene_nts_update(ffc_scene *s, const double u[], long nrows, const double m[], long *changes, long *bad);

/* The contact residual of the node-to-surface pairs, which
 * ffc_scene_assemble leaves out (their forces come from multipliers):
 * added into R[nv*3] from the forces of the last ffc_scene_nts_update,
 * -f on each contact node and L_a f on the nodes of its master facet (f
 * the force on the slave node, L its foot's area coordinates), the sign
 * of ffc_scene_assemble's residual.  The supports' reactions of a
 * node-to-surface scene need it where a prescribed dof carries contact. */
int ffc_scene_nts_force(const ffc_scene *s, double R[]);

/* Statistic `name` of pair k (k = -1: all pairs, summed or the largest)
 * from the last assembly (maxDlam, maxDlamT, maxPenNode: the last
 * augmentation), or with step != 0 as they were at the last commit (the
 * converged step: its slip and friction states, which an assembly after
 * the commit no longer sees).  FFC_ERR_LABEL for a name that is not a
 * statistic; ffc_scene_stat_name(i) lists them (NULL past the last). */
int ffc_scene_stat(const ffc_scene *s, int pair, const char *name, int step, double *value);
const char *ffc_scene_stat_name(int i);

/* Links of pair k (k = -1: all pairs). */
long ffc_scene_nlinks(const ffc_scene *s, int pair);

/* ffc_points rows of pair k (k = -1: every pair in order) into
 * P[cap*FFC_POINT_COLS]; *n the rows (needed, with FFC_ERR_CAPACITY).
 * Mortar pairs give the rows of ffc_points_nodes, one per slave node;
 * ffc_scene_npoints: the number of rows. */
long ffc_scene_npoints(const ffc_scene *s, int pair);
int ffc_scene_points(const ffc_scene *s, const double u[], int pair, long cap, double P[], long *n, long *bad);

/* Copies of pair k's multipliers lam[nlam] and lam_t[3 nlam] (either may
 * be NULL); *n = nlam (nodes for the nodal law, links otherwise). */
int ffc_scene_multipliers(const ffc_scene *s, int pair, long cap, double lam[], double lam_t[], long *n);

/* The contact mesh size of pair k (k = -1: all pairs): the smaller of
 * the mean longest facet edge of its slave and of its master surface, in
 * the reference configuration (length); FFC_ERR_EMPTY without pairs. */
int ffc_scene_facet_size(const ffc_scene *s, int pair, double *h);

/* Plane-strain modulus E' = E / (1 - nu^2) = 4 mu (lambda + mu) / (lambda + 2 mu)
 * from Lame's constants (force/length^2). */
double ffc_plane_modulus(double lame1, double lame2);

/* Automatic penalty of pair k from the plane-strain modulus of the body
 * behind each facet, Ep_s[nfs] and Ep_m[nfm] (in the pair's facet order):
 *     eps_N = 200 / (1 / k_s + 1 / k_m),   k = mean over a side's facets of E' / h,
 * h the facet's longest edge.  k is the stiffness of one element layer
 * under that side; the two layers act in series.  For equal bodies and
 * facets this is 100 E' / h: before augmentation a pressure p penetrates by
 * p h / (100 E'), a hundredth of one layer's compliance, the value that
 * needed the fewest Newton iterations on the patch and Hertz cases (10x
 * smaller: 2-3x more augmentations; 10x larger: Newton fails on Hertz).
 * A soft body against a stiff one gets about 200 times the soft layer's
 * stiffness: the penetration stays a small part of the soft side's
 * deformation.  FFC_ERR_VALUE for a modulus that is not positive. */
int ffc_scene_auto_penalty(const ffc_scene *s, int pair, const double Ep_s[], const double Ep_m[], double *eps);

/* Facets of pair k's slave (master = 0) or master side. */
long ffc_scene_nfacets(const ffc_scene *s, int pair, int master);

/* A rigid motion of one body: a translation (w = 0: t the unit direction,
 * p the body's centroid) or a turn about the axis through p along the unit
 * w, with the slide t along it per radian (0 for a pure rotation).
 * Translations and axes lie along the coordinate axes where the free
 * motions allow. */
typedef struct {
    long body;   /* the body's lowest node index */
    long tet;    /* the body's first tetrahedron (index into T) */
    double x[3]; /* that node's reference position (length) */
    double t[3]; /* translation direction (unit), or slide per radian along the axis (length) */
    double w[3]; /* unit axis of the turn; 0 for a translation */
    double p[3]; /* a point of the axis: the one nearest the body's centroid (length) */
    double amount; /* how far u moved the body along it (least squares over the body's nodes): a turn's
                      angle about w (radians), a translation's length along t at the centroid; 0 without u */
} ffc_motion;

/* The rigid motions of each body that the prescribed dofs leave free: the
 * bodies are the tetrahedra T[nt*4] joined by shared nodes (nodes in no
 * tetrahedron are left out), fixed[nv*3] nonzero on a prescribed dof (NULL:
 * none).  Per body a basis of its free motions, translations first, each
 * with its amount in the displacement u[nv*3] (NULL: none); *n the count
 * over all bodies, FFC_ERR_CAPACITY (with *n) when it exceeds cap. */
int ffc_rigid_free(long nv, const double X[], long nt, const long T[], const double fixed[], const double u[],
                   long cap, ffc_motion out[], long *n);

/* ffc_rigid_free on the scene's tetrahedra and its prescribed dofs
 * (ffc_scene_set_fixed; none given: every rigid motion is free), amounts
 * in u (NULL: none); FFC_ERR_EMPTY for a scene made without tetrahedra. */
int ffc_scene_free_motions(const ffc_scene *s, const double u[], long cap, ffc_motion out[], long *n);

/* ffc_volume_check of the scene's tetrahedra at X + u. */
int ffc_scene_check_volume(const ffc_scene *s, const double u[], long *bad);

/* mask[n] (n = 3 nv): 1 on the three dofs of every node of a slave or a
 * master facet of any pair, 0 elsewhere.  Returns the number of such
 * nodes, or a negative status (FFC_ERR_SIZE for n != 3 nv). */
long ffc_scene_surface_mask(const ffc_scene *s, long n, double mask[]);

/* Bulk factorization of a small-strain scene.  The scene keeps the bulk
 * stiffness K (n = 3 nv dofs, node-major: dof 3 i + c is component c of
 * node i; symmetric positive definite once the Dirichlet rows carry a
 * large diagonal, FreeFEM's tgv) and solves each Newton system
 * (K + Kc) x = b on the contact dofs (the contact-reduced solve below):
 * K + S is factorized (CHOLMOD) at the first solve, S = s I on the dofs of
 * that first contact tangent (s the mean diagonal of the rows that are not
 * Dirichlet rows: a body that only contact holds makes K singular); the
 * compliance G of the contact dofs grows by block solves (pruned to
 * the rows read) when Kc touches new dofs; each solve is two back-solves and a dense LU of
 * I + G Kcc (m x m, LAPACK), then at most two steps of iterative
 * refinement.  Dirichlet rows are those whose diagonal is at least 1e12
 * times the median diagonal: their value is b_i / K_ii (the tgv rows'
 * solution to within 1/tgv) and they are eliminated before the
 * factorization, so that CHOLMOD's condition estimate shows a singular K
 * (below 1e-12: refused). */
typedef struct {
    long factorizations; /* of K + S (count) */
    long columns;        /* compliance columns computed (count) */
    long solves;         /* ffc_scene_solve calls (count) */
    long backsolves;     /* right-hand sides solved with the factor (count) */
    long refinements;    /* iterative-refinement steps (count) */
    long kept;           /* condensed Newton directions solved by GMRES preconditioned with the last dense LU
                            of the same support (count) */
    long m;              /* contact dofs in the compliance (count) */
    double shift;        /* s (force/length; 0: no shift) */
    long shifted;        /* dofs that carry the shift (count; 0: none) */
    double rcond;        /* CHOLMOD's estimate of the factor's reciprocal condition (1; 0 with MUMPS,
                            which refuses negative pivots and those below 1e-12 of K's norm instead) */
    int ranks;           /* the ranks that share the factorization (1: CHOLMOD) */
    double factor_mb;    /* MUMPS: this rank's factorization memory (MB; 0 with CHOLMOD) */
    double factor_mb_max; /* MUMPS: the largest rank's (MB) */
    double residual;     /* last solve: the free rows' residual / (|b_free| + max free
                            diagonal |x_free|), or a Dirichlet row's residual / (its
                            diagonal |x|_inf), the larger (1) */
    double t_factor;     /* wall time of the factorizations (seconds) */
    double t_columns;    /* wall time of the compliance columns (seconds) */
    long reused;         /* condensed Newton calls whose first solve was the last call's closing one (count) */
    int factor_ranks;    /* CHOLMOD on every rank: the ranks of this machine that made the factor together, each
                            then holding all of it (1: this rank made its own) */
    int factor_split;    /* of them, the ranks that made the last factorization's subtrees, each its share,
                            before the supernodes above them (1: one rank made it all) */
    double t_backsolves; /* wall time of the single back-solves (seconds) */
    long split_solves;   /* of those, the ones the machine's ranks split by the factor's subtrees (count) */
} ffc_solve_info;

/* Sets K from its triplets (Ti, Tj, Tv)[nt] (both triangles; duplicates
 * summed), n = 3 nv; any factorization and compliance of an earlier K are
 * dropped.  mmax: contact dofs a solve takes at most (its dense LU grows
 * as m^3).  FFC_ERR_INDEX / FFC_ERR_NONFINITE (*bad = the triplet),
 * FFC_ERR_SINGULAR for a diagonal entry that is not positive (*bad = the
 * dof), FFC_ERR_SIZE when n is not 3 nv. */
int ffc_scene_set_bulk(ffc_scene *s, long n, long nt, const long Ti[], const long Tj[], const double Tv[], long mmax,
                       long *bad);

/* Where a scene's bulk matrix is factorized and solved. */
typedef enum {
    FFC_ENGINE_CHOLMOD = 0,   /* CHOLMOD, in this process (the default) */
    FFC_ENGINE_MUMPS = 1,     /* parallel MUMPS over an MPI communicator: every rank of it holds the
                                 same scene and makes the same calls in the same order; each hands
                                 MUMPS a share of K's entries, and every rank receives each solution */
    FFC_ENGINE_REPLICATED = 2 /* CHOLMOD on every rank of an MPI communicator, each holding the whole
                                 factor (the same calls in the same order, as for MUMPS); the
                                 compliance columns of the condensed path are shared out over the
                                 ranks and gathered.  Small-strain bulks only (ffc_scene_set_bulk):
                                 faster than MUMPS on a few ranks while one process's memory holds
                                 the factor */
} ffc_engine;
typedef struct {
    ffc_engine engine;   /* the engine */
    int comm;            /* FFC_ENGINE_MUMPS: the communicator as a Fortran handle
                            (MPI_Comm_c2f(MPI_COMM_WORLD)) */
    int own;             /* ffc_parallel_solve: 0, every rank passes the same entries (each hands
                            MUMPS its share); 1, each rank passes its own (A is their sum: a
                            matrix assembled on each rank's part of the mesh) */
    int links;           /* ffc_scene_set_parallel: 1, the condensed Newton's contact evaluations
                            (augmented Lagrangian pairs with nodal multipliers, no mortar segments,
                            the residual and the ranked tangent) shared out, each rank the links of
                            its share of the slave facets, their sums gathered in rank order; 0,
                            every rank evaluates every link */
} ffc_parallel;
/* Sets the engine of the next ffc_scene_set_bulk.  FFC_ERR_VALUE for an
 * unknown engine, FFC_ERR_UNAVAILABLE for MUMPS or the replicated CHOLMOD
 * in a build without MPI (ffc_has_mpi() == 0) or for MUMPS before
 * MPI_Init (at ffc_scene_set_bulk). */
int ffc_scene_set_parallel(ffc_scene *s, const ffc_parallel *p);
/* Solves A x = b[n] once, A a general sparse matrix (a full Newton
 * system: non-symmetric with friction, indefinite with multipliers) from
 * its triplets (Ti, Tj, Tv)[nt] (duplicates summed), by parallel MUMPS
 * over p->comm: every rank passes the same b, and the same entries (each
 * hands MUMPS its share) or, with p->own, its own entries (A is their
 * sum); x on every rank.  FFC_ERR_INDEX /
 * FFC_ERR_NONFINITE (*bad = the triplet, or the entry of b),
 * FFC_ERR_SINGULAR (an exactly zero pivot; as with UMFPACK, a tiny one
 * gives a huge solution: the caller checks the residual), FFC_ERR_UNAVAILABLE
 * without MPI or for p->engine = FFC_ENGINE_CHOLMOD (one process: FreeFEM's
 * UMFPACK); FFC_ERR_VALUE for FFC_ENGINE_REPLICATED (a full system is
 * MUMPS's). */
int ffc_parallel_solve(const ffc_parallel *p, long n, long nt, const long Ti[], const long Tj[], const double Tv[],
                       const double b[], double x[], long *bad);
/* A full solver: A x = b for a general sparse A (a Newton system of the
 * whole mesh: not symmetric with friction, indefinite with multipliers)
 * by UMFPACK, in this process.  The pattern of the last call is kept:
 * a call with the same order and the same (Ti, Tj) in the same order
 * reuses its analysis (ordering and symbolic factorization) and only
 * factorizes numerically. */
typedef struct ffc_full ffc_full;
int ffc_full_create(ffc_full **out);
void ffc_full_free(ffc_full *f);
/* Solves A x = b[n], A from its triplets (Ti, Tj, Tv)[nt] (duplicates
 * summed).  FFC_ERR_INDEX / FFC_ERR_NONFINITE for a bad entry,
 * FFC_ERR_SINGULAR for an exactly zero pivot (a tiny one gives a huge
 * solution: the caller checks the residual), FFC_ERR_MEMORY; err (may be
 * NULL) names the cause. */
int ffc_full_solve(ffc_full *f, long n, long nt, const long Ti[], const long Tj[], const double Tv[],
                   const double b[], double x[], ffc_error *err);
/* Its counters (factorizations, backsolves, rcond) and the patterns it analysed. */
int ffc_full_info(const ffc_full *f, ffc_solve_info *info, long *analyses);
/* 1 in a build with MPI and parallel MUMPS (-DFFC_MPI), else 0. */
int ffc_has_mpi(void);

/* MPI_COMM_WORLD: this process's rank, the ranks, the communicator as a
 * Fortran handle (0, 1, 0 in a build without MPI or outside MPI_Init). */
int ffc_mpi_world(int *rank, int *size, int *fcomm);
/* v[n] replaced on every rank by its sum (op 0), largest (1) or smallest
 * (2) value over the ranks; a collective call (nothing with one rank). */
int ffc_mpi_allreduce(double v[], long n, int op);
/* Every rank's triplets (Ti, Tj, Tv)[nt], concatenated in the order of
 * the ranks, into (Oi, Oj, Ov)[cap] on every rank; *total = their count
 * (FFC_ERR_CAPACITY when cap is smaller: call again with cap >= *total;
 * FFC_ERR_SIZE for a negative count or cap, or over 2^31 - 1 in all).
 * Pieces of one matrix assembled on parts of a mesh become its triplets on
 * every rank (ffc_triplets_sum sums them, the same bits everywhere).  A
 * collective call: a bad argument on one rank is every rank's error (the
 * most negative status).  One rank: a copy. */
int ffc_mpi_gather_triplets(long nt, const long Ti[], const long Tj[], const double Tv[], long cap, long Oi[],
                            long Oj[], double Ov[], long *total);
/* Waits for every rank (nothing with one rank). */
int ffc_mpi_barrier(void);
/* This process's peak resident memory (MB). */
double ffc_peak_mb(void);

/* Solves (K + Kc) x = b[n], Kc from the triplets (Ti, Tj, Tv)[nt].
 * FFC_ERR_EMPTY without a K; FFC_ERR_INDEX / FFC_ERR_NONFINITE (*bad =
 * the triplet, or the entry of b); FFC_ERR_CAPACITY when Kc touches more
 * than mmax contact dofs (*bad = their count); FFC_ERR_SINGULAR when K + S
 * is not positive definite or the solve's residual stays above 1e-6. */
int ffc_scene_solve(ffc_scene *s, long nt, const long Ti[], const long Tj[], const double Tv[], const double b[],
                    double x[], long *bad);

/* Counters of the bulk solves since the last ffc_scene_set_bulk (zero
 * without a K). */
int ffc_scene_solve_info(const ffc_scene *s, ffc_solve_info *info);

/* Newton's method on the condensed contact problem of a small-strain
 * augmented Lagrangian scene at fixed links and multipliers (the inner
 * loop of an augmentation, run in C on the contact dofs only).
 *
 * Formulation: the bulk is linear, r(u) = K u - f + F_c(u) on the free
 * dofs.  From u (residual r[n] given), the increment d solves
 * K d + F_c(u + d) = b' = -(r - F_c(u)).  Let C be the free dofs that
 * the contact force (or its tangent) has reached, G = P_C K^-1 P_C^T their
 * compliance (pruned block solves, kept between calls), d0 = K^-1 b'.  The
 * free dofs outside C carry no contact force, so with y = d_C the
 * interior is eliminated exactly and
 *     rho(y) = G^-1 (y - d0_C) + F_c(u + d)_C = 0     (m equations)
 * is the residual of the full system at the equilibrated interior.  Its
 * Jacobian is G^-1 + Kc_CC; the Newton step solves
 *     (I + G Kc_CC) dy = -G rho,
 * reduced to the dofs a that Kc touches (Kc_CC = E_a M E_a^T: t + G_aa M
 * t = -(G rho)_a, dy = -G rho - G_Ca M t), an |a| x |a| dense LU.  The
 * line search is the scene driver's: the root of g(s) = rho(y + s dy) . dy
 * by regula falsi (Illinois); a direction with g(0) >= 0 is replaced by
 * the material tangent's.  The primary unknown is the reaction
 * z = G^-1 (y - d0_C) that holds C at y: the Newton equation gives its
 * step, dz = -rho - Kc_CC dy, and y = d0_C + G z is recomputed from it
 * (no drift between the two; a Cholesky factor of G gives only the
 * start, y = 0: C held at u, the interior equilibrated).  C grows as the
 * contact does: the contact evaluation reads the dofs R of the pairs'
 * facets, whose displacement u + d0 + H z comes from the compliance
 * columns kept on those rows (H = P_R K^-1 P_C^T, |R| x |C|); a force or
 * tangent entry on a dof of R outside C makes it join C with z = 0 (the
 * same state), at the start (the start is then taken again: at the first
 * call of a load step the rest moves by the whole increment, and what it
 * reaches is held at u too), at an iterate, or at a line-search point
 * (the iteration is then taken again).  C thus holds the dofs in contact
 * at some point of the solve, not every linked point's (Hertz P1 h_c =
 * 0.025: 855 columns instead of 1,343).  At the end
 * d = d0 + K^-1 P_C^T z (one back-solve): the state whose residual is
 * rho.  With the shift S of a singular K (see above), K + S and
 * F_c - S y take the place of K and F_c.  A dynamic scene's velocities
 * follow u: v = v0 + dvdu (u + d - u).  Per call: two back-solves, one
 * contact evaluation per iteration and line-search point, a column per
 * dof that joins C, the Cholesky factor of G extended when C grew.  A
 * singular K (a body that only contact holds) is shifted on three nodes
 * far apart (by K's graph) in each body that the linked points' facets or
 * the contact force at u touch: no rigid motion of such a body leaves
 * them all at rest, and each shifted dof adds one term to the dense
 * systems (ffc_solve_info.shifted counts them); should K + S still be
 * singular, on the nodes the force reaches, then on the linked points'
 * facets.  The shifted dofs belong to C. */
/* Why a load (or time) step of the scene driver stopped: solveScene()'s
 * status (the script's constants ffcStep...), which its augmentation loop
 * returns too. */
typedef enum {
    FFC_STEP_CONVERGED = 0,
    FFC_STEP_AUGMENT = 1,   /* the augmentations (node-to-surface: the active set) did not settle */
    FFC_STEP_NOPAIR = 5,    /* the scene has no contact pair */
    FFC_STEP_MATERIAL = 6,  /* a region without its material (or density, in time) */
    FFC_STEP_TIME = 7,      /* time steps asked of a scene that has none, or none of one that needs them */
    FFC_STEP_SETTINGS = 8,  /* settings that do not go together (a solver or a method the bulk cannot take) */
    FFC_STEP_NEWTON = 10    /* plus an ffc_newton_reason: Newton stopped short */
} ffc_step_reason;
enum { FFC_NEWTON_HIST = 64 };
/* Why a Newton loop stopped: the condensed Newton's return value, and the
 * scene driver's Newton's (the same values in the script). */
typedef enum {
    FFC_NEWTON_CONVERGED = 0,  /* the residual met the tolerance */
    FFC_NEWTON_MAXIT = 1,      /* the iteration limit */
    FFC_NEWTON_NODESCENT = 2,  /* no direction that lowers the residual, or no admissible step along it */
    FFC_NEWTON_LINEAR = 3,     /* the linear solve failed (a singular or inaccurate system) */
    FFC_NEWTON_CAPACITY = 4    /* the condensed system would hold more contact dofs than allowed */
} ffc_newton_reason;
typedef struct {
    int max_iter;      /* Newton iterations at most (>= 1) */
    int max_ls;        /* line-search evaluations per iteration (>= 0; 0: full steps) */
    double ls_tol;     /* a step is taken once |g(s)| <= ls_tol |g(0)| (0 < ls_tol < 1) */
    double ftol;       /* converged when |rho| <= max(ftol, frel x the contact force
                          scale) (force), > 0 */
    double frel;       /* relative tolerance (1), >= 0; the scale is the largest
                          |Fx| + |Fy| + |Fz| of the total normal contact force met */
    int tangent;       /* FFC_TANGENT_CONSISTENT, FFC_TANGENT_MATERIAL or FFC_TANGENT_RANKED
                          (every pair on the nodal law; after two ranked iterations that did not
                          reduce the residual 10x, the call goes on with the consistent tangent) */
    long max_dofs;     /* contact dofs C may hold (count), >= 0; 0: the bulk's mmax */
    int min_iter;      /* iterations taken even when the start meets the tolerance (0 or 1; 1 after
                          an augmentation: multipliers that changed at a node of small weight move
                          the residual by less than the tolerance, and without a step the next
                          augmentation would repeat the same change) */
} ffc_newton_opts;

typedef struct {
    int iters;         /* Newton iterations (condensed linear solves) */
    int evals;         /* contact evaluations */
    int evals_shared;  /* of them, those whose links the ranks shared out (ffc_parallel.links) */
    double t_eval;     /* wall time of those evaluations (seconds) */
    int fallbacks;     /* directions taken from the material tangent */
    int switched;      /* 1: FFC_TANGENT_RANKED gave way to the consistent tangent (two ranked
                          iterations that did not reduce the residual 10x) */
    long m;            /* contact dofs of the condensed problem at the end (count) */
    long grown;        /* of them, those that joined during the call (count) */
    long support;      /* the largest dense system solved (count) */
    double res;        /* |rho| at the end (force) */
    int reason;        /* why it stopped (ffc_newton_reason) */
    int nhist;         /* entries of hist */
    double hist[FFC_NEWTON_HIST]; /* |rho| at each iteration's start, then the last (force) */
} ffc_newton_info;

/* Defaults: max_iter 25, max_ls 8, ls_tol 0.5, ftol 0 (must be set),
 * frel 0, consistent tangent, max_dofs 0, min_iter 0. */
ffc_newton_opts ffc_newton_defaults(void);

/* Runs the condensed Newton from u[n] (n = 3 nv) with its residual r[n]
 * (FreeFEM's tgv rows included: a Dirichlet row's r / K_ii is the error
 * of its value, which the first step removes); u is the converged
 * displacement on FFC_NEWTON_CONVERGED, the last iterate on
 * FFC_NEWTON_MAXIT and FFC_NEWTON_NODESCENT (the returned reason),
 * unchanged on an error (a negative status).  FFC_ERR_EMPTY without a
 * bulk matrix, FFC_ERR_VALUE for a scene with node-to-surface pairs (or,
 * with FFC_TANGENT_RANKED, pairs with multipliers at quadrature points) or
 * options out of range, FFC_ERR_CAPACITY when C would hold more than
 * max_dofs (or the bulk's mmax) dofs (*bad = their count; the columns
 * added before stay, u is unchanged), FFC_ERR_SINGULAR when K + S or a
 * condensed system cannot be factorized, FFC_ERR_NONFINITE (*bad = the
 * entry of r or u). */
int ffc_scene_newton(ffc_scene *s, const double r[], double u[], const ffc_newton_opts *o, ffc_newton_info *info,
                     long *bad);


/* ------------------------------------- node-to-surface Lagrange multipliers */
/* Each slave node c is paired with the master facet (i, j, k) under it:
 * area coordinates L of the foot, unit master normal n, gap
 * g = n . (x_c - sum_a L_a x_a).  With the relative displacement
 * D u = u_c - sum_a L_a u_a (3 x ndof), the constraint rows are
 *   slide:  n^T D u = n^T D u^k - g^k        (one row: the linearized gap
 *                                             vanishes; exact for flat facets)
 *   stick:  the slide row and t_i^T D u = t_i^T D u^n, i = 1, 2  (no
 *           tangential motion over the master since the last converged
 *           step u^n; t_1, t_2 an orthonormal tangent basis of n)
 *   slide with friction: the slide row and two sliding rows, Coulomb's
 *           law linearized at the last iterate (see ffc_nts_rows)
 *   open:   none.
 * The saddle-point system  [K  Bf^T; B  C] [u; m] = [f; c]  gives the
 * multipliers m; the contact force on the slave node is -(Bf^T m) at its
 * dofs: F = -m_n n - m_1 t_1 - m_2 t_2 with friction (stick or slide),
 * F = -m_n n without; all scaled by law->scale.  Bf = B and C = 0 except
 * on sliding rows with friction, whose B holds M t_a (the slip's part)
 * and C the multipliers' part of the linearized law.
 * Transitions (ffc_nts_update): open -> contact when g < -gtol (stick if
 * nu_s > 0 and the node has not moved tangentially since u^n, else slide
 * along that motion); contact -> open when F_n < -ftol max F_n
 * (tension release); stick -> slide when |F_t| > nu_s F_n (1 + 1e-9)
 * (d = -F_t/|F_t|);
 * slide -> stick when |q| <= nu_d F_n, with q = -F_t + c s, s the
 * tangential slip since the last converged step, c = law->scale (the
 * projection form of Coulomb's law: a primal-dual active-set rule, noise
 * in s does not flip the state); else the node slides along d = q / |q|.
 * With the sliding rows' Newton linearization the active-set loop is a
 * semi-smooth Newton method.  Chattering guard: once a node has changed state
 * max_flips times in one load step, each update makes one change only,
 * at the first node in order that asks for one (the least-index rule,
 * which terminates for frictionless contact, a P-matrix complementarity
 * problem, where changing every violated node at once may cycle).  A
 * node that has changed state 2 max_flips times stays open for the rest of
 * the step (stats->locked; its penetration is min_gap_open). */
enum { FFC_NTS_OPEN = 0, FFC_NTS_STICK = 1, FFC_NTS_SLIDE = 2 };

typedef struct {
    double nu_s;       /* static friction coefficient (1), >= 0 */
    double nu_d;       /* dynamic friction coefficient (1), 0 <= nu_d <= nu_s */
    double gtol;       /* an open node enters contact when g < -gtol (length), >= 0 */
    double ftol;       /* tension release when F_n < -ftol * max F_n (1), >= 0 */
    int max_flips;     /* state changes of a node per load step before the
                          chattering guard acts (>= 1) */
    double scale;      /* rows and right-hand sides are multiplied by scale (force/length,
                          e.g. E h: balances the saddle-point matrix); > 0 */
} ffc_nts_law;

/* One slave node: its state (carried across iterations and steps) and its
 * geometry and force (refreshed by each call). */
typedef struct {
    long node;         /* slave node (pair numbering) */
    double area;       /* tributary area int N_c dA on the slave surface (length^2) */
    int state;         /* FFC_NTS_* */
    int flips;         /* state changes in the current load step */
    int chatter;       /* 1 once the node reached max_flips changes in this step */
    double dir[3];     /* sliding direction d of the slave over the master (1) */
    long mf;           /* master facet under the node, -1 for none */
    double L[3];       /* area coordinates of the foot (1) */
    double n[3];       /* unit master normal at the foot (1) */
    double gap;        /* g (length) */
    double slip[3];    /* tangential motion over the master since u^n (length) */
    long row;          /* first constraint row, -1 for none */
    int rmask;         /* rows present: bit 0 normal, bits 1, 2 tangents (friction) */
    double nr[3];      /* normal the rows were built with (1) */
    double f[3];       /* contact force on the slave node (force) */
    double fn;         /* its normal part n_r . f, > 0 compressive (force) */
    long mfprev;       /* master facet before the last change of mf in this step, -1 for none */
    int frozen;        /* 1: mf is kept for the rest of the step (no search) */
    int tfix;          /* prescribed tangential dof of the node (set by ffc_nts_rows):
                          0 none, k + 1 for dof k, 4 for two or more */
} ffc_nts_node;

/* Summary of an update. */
typedef struct {
    long changes;      /* state changes made by this update */
    long open, stick, slide; /* nodes in each state after it */
    long chatter;      /* nodes that reached max_flips: the guard acts (one change per update) */
    long released;     /* contact -> open changes in this update */
    long locked;       /* open nodes that penetrate but were kept open: they changed
                          state 2 max_flips times in this step (min_gap_open shows
                          their penetration) */
    double max_pen;    /* largest penetration max(0, -g) over contact nodes (length) */
    double min_fn;     /* smallest F_n over the nodes that had rows (force; 0 if none):
                          negative when a node was released */
    double min_gap_open; /* smallest gap over open nodes with a partner (length; 0 if none) */
    double max_ddir;   /* largest change |d_new - d_old| of a sliding direction (1) */
    double force[3];   /* total contact force on the slave nodes (force) */
    double max_ratio;  /* largest |F_t| / F_n over contact nodes (1) */
    double max_gap_err; /* largest |g| over nodes that had rows and stay in contact:
                          the geometric error of the linearized rows (length) */
    double max_slide_res; /* largest |F_t + nu_d F_n d| over nodes that slide on,
                          divided by the largest F_n: Coulomb's law's residual (1) */
} ffc_nts_stats;

/* The distinct nodes of the slave facets of pair (3-node facets), in
 * ascending order, with their tributary areas in the reference
 * configuration; state open.  cap: capacity of out[].  Returns the
 * number of nodes (FFC_ERR_CAPACITY with *need set when cap is short). */
long ffc_nts_nodes(const ffc_pair *pair, long cap, ffc_nts_node out[], long *need);

/* Pairs each node with the master facet under it at x = X + u (search
 * options o, NULL for the defaults) and refreshes mf, L, n, gap and
 * slip (against pair->u_prev; zero when it is NULL).  A contact node
 * whose facet returns to the one it had before (A -> B -> A: it sits in a
 * valley of the master between two facets, and one facet's constraint
 * puts it into the other) is frozen: it keeps that facet, projected onto
 * it (onto its boundary when the foot is outside), until the caller
 * clears frozen and mfprev (at the next load step).  A contact node the
 * search leaves without a partner keeps its facet when its foot lies past
 * the master's rim by no more than its distance |g| to the facet's plane
 * (a node held in a symmetry plane that cuts the master at its rim).  A
 * contact node whose foot lies on its facet to 1e-9 in local coordinates
 * keeps it where the search gives another (a vertex or an edge the two
 * share: which one is round-off, and their normals differ).  With init != 0 the
 * state is also set: contact (stick if law->nu_s > 0, else slide) when
 * g <= law->gtol, open otherwise. */
int ffc_nts_locate(const ffc_pair *pair, const ffc_nts_law *law, const ffc_search_opts *o,
                   int init, long nn, ffc_nts_node nodes[]);

/* Constraint rows of the contact nodes (geometry of the last locate), as
 * triplets (Bi, Bj) with values Bv (B) and Fv (Bf), and right-hand side
 * c[]; a column Bj >= 3 nv is column Bj - 3 nv of the multiplier block C
 * (value in Bv, Fv = 0: sliding rows with friction); entries on dofs with fixed[dof] != 0 (Dirichlet; fixed may be
 * NULL) are moved to c with the value in pair->u, and a row left empty
 * is dropped.  cap: capacity of the triplet arrays, ccap of c.
 * Writes *ntrip and *nrows (or the sizes needed with FFC_ERR_CAPACITY)
 * and each node's row, nr and tfix.  With friction, a contact node whose
 * slave dof k is held at zero in a tangential direction (fixed > 0,
 * |n_k| < 0.9, e.g. on a symmetry plane) has no row along that direction
 * t1 (e_k in the tangent plane: the support carries that force, and the
 * row would be nearly empty); stick and slide act along t2 = n x t1 alone
 * (Coulomb's law in one dimension); with two such dofs the node keeps its
 * normal row only.  A dof moved (fixed < 0: a face pushed along the
 * contact plane) keeps its row. */
int ffc_nts_rows(const ffc_pair *pair, const ffc_nts_law *law, const double fixed[],
                 long nn, ffc_nts_node nodes[], long cap, long Bi[], long Bj[],
                 double Bv[], double Fv[], long ccap, double c[], long *ntrip, long *nrows);

/* After a solve: forces from the multipliers m[nrows] of the rows built
 * last, then the transitions (see above) with the geometry of the last
 * locate (call ffc_nts_locate at the new displacement first). */
int ffc_nts_update(const ffc_nts_law *law, long nrows, const double m[], long nn,
                   ffc_nts_node nodes[], ffc_nts_stats *st);

/* Number of rows the nodes' row and rmask fields describe (the size of the
 * multiplier vector of the last ffc_nts_rows). */
long ffc_nts_nrows(long nn, const ffc_nts_node nodes[]);

/* One row per node in the columns of ffc_points, P[nn*FFC_POINT_COLS]:
 * x, y, z at X + u (nv nodes), gap, pressure F_n / area (0 when open),
 * in contact, area, master facet, tangential traction on the slave
 * F_t / area (x, y, z), state FFC_NTS_*, dissipation density
 * |F_t . slip| / area.  Returns the nodes in contact; FFC_ERR_INDEX or
 * FFC_ERR_VALUE (area <= 0) with *bad = the node row at fault. */
int ffc_nts_points(long nv, const double X[], const double u[], long nn, const ffc_nts_node nodes[],
                   double P[], long *bad);

/* ------------------------------------------- contact-reduced linear solve */
/* Formulation.  In a small-strain quasi-static scene the bulk stiffness K
 * (n x n, symmetric, Dirichlet rows included) does not change: it is
 * factorized once, and the contact tangent Kc, which touches only the m
 * contact dofs C (Kc = P Kcc P^T, P the n x m selection), is handled on
 * those dofs.  With G = P^T K^-1 P (m x m, the compliance of the contact
 * dofs; column j is K^-1 e_dof[j] at the contact dofs, one back-solve) and
 * y = K^-1 b:
 *     (K + P Kcc P^T) x = b   <=>   (I + G Kcc) x_C = y_C,
 *                                   x = y - K^-1 P (Kcc x_C),
 * so a Newton iteration costs two back-solves with K and one dense m x m
 * solve instead of a factorization of K + Kc.  G only grows: a dof that
 * Kc touches for the first time adds one column (and, K being symmetric,
 * the same row).  Kcc may be non-symmetric (friction).  A body held only
 * by contact makes K singular: then K + S is factorized instead, S = diag(sh)
 * non-zero only on contact dofs, and Kcc - S_CC takes Kcc's place (exact:
 * K + Kc = (K + S) + P (Kcc - S_CC) P^T). */

/* The dofs that the triplets (Ti, Tj, Tv)[nt] of an n x n matrix touch
 * with a non-zero value (row or column) and that are not among dof[m]:
 * written to out[cap] in ascending order, *nout their count (or the count
 * needed, with FFC_ERR_CAPACITY).  pos[n] is work space (on return all -1).
 * FFC_ERR_INDEX when an index is outside [0, n). */
int ffc_reduced_missing(long n, long m, const long dof[], long nt, const long Ti[], const long Tj[],
                        const double Tv[], long cap, long out[], long *nout, long pos[]);

/* Appends the dof j to dof[m] (capacity ld) and the column x[n] = K^-1 e_j
 * to G (column-major, leading dimension ld): G(i, m) = G(m, i) = x[dof[i]]
 * for i < m, G(m, m) = x[j].  FFC_ERR_CAPACITY when m >= ld, FFC_ERR_INDEX
 * for j outside [0, n) or already in dof[], FFC_ERR_NONFINITE for a
 * non-finite x at the contact dofs. */
int ffc_reduced_add(long n, long ld, long m, long dof[], double G[], const double x[], long j);

/* Solves (I + G Kcc') x_C = y_C with Kcc' = Kcc - diag(sh) at the contact
 * dofs (sh[n] may be NULL: no shift), Kcc from the triplets (Ti, Tj,
 * Tv)[nt] (global dofs, each in dof[m]), and writes w[n] = P (Kcc' x_C)
 * (zero off the contact dofs); xc[m] receives x_C.  Work: A[m*m], piv[m],
 * pos[n] (on return all -1).  FFC_ERR_INDEX when a triplet or a non-zero
 * shift touches a dof outside dof[] (call ffc_reduced_missing / _add
 * first), FFC_ERR_SINGULAR on a zero pivot, FFC_ERR_NONFINITE for
 * non-finite input. */
int ffc_reduced_solve(long n, long ld, long m, const long dof[], const double G[], long nt, const long Ti[],
                      const long Tj[], const double Tv[], const double sh[], const double y[], double xc[],
                      double w[], double A[], long piv[], long pos[]);

/* -------------------------------------------------------- sparse triplets */
/* Sums the duplicates of the triplets (Ti, Tj, Tv)[nt] of an n x n matrix
 * into (Ci, Cj, Cv) (capacity nt: the sum never has more), grouped by row
 * in ascending order, columns within a row in order of first appearance;
 * returns the number of distinct entries.  Work: rp[n + 1], w[n].  The
 * contact tangent of the nodal law repeats entries about 12 times (Hertz):
 * summing them here hands FreeFEM a matrix, not a list to hash.
 * FFC_ERR_INDEX for an index outside [0, n). */
long ffc_triplets_sum(long n, long nt, const long Ti[], const long Tj[], const double Tv[], long Ci[],
                      long Cj[], double Cv[], long rp[], long w[]);

/* ------------------------------------------------ linear elasticity */
/* The stiffness matrix of isotropic linear elasticity on linear
 * tetrahedra: int lambda div u div v + 2 mu eps(u) : eps(v), for the
 * displacement field [P1, P1, P1] whose dof 3 i + c is component c of
 * vertex i (nv vertices X[3 nv]; nt tetrahedra T[4 nt]; Lame's lambda
 * lam[nt] and mu mu[nt], constant per tetrahedron).  Its distinct entries
 * go to (Ki, Kj, Kv)[cap], *nnz of them: row by row (ascending), columns
 * ascending within a row, both triangles (the matrix is symmetric); the
 * count needed is 9 x (vertex pairs that share a tetrahedron, each vertex
 * with itself included), *nnz with FFC_ERR_CAPACITY.  FFC_ERR_INDEX for a
 * vertex index outside [0, nv), FFC_ERR_NONFINITE for a coordinate (*bad =
 * the vertex) or a Lame constant (*bad = the tetrahedron) that is NaN or
 * Inf, FFC_ERR_DEGENERATE for a tetrahedron of zero volume (|det J| <=
 * 1e-13 |e1| |e2| |e3|, J = [e1 e2 e3] its edges from the first vertex;
 * *bad = it). */
int ffc_elastic_p1(long nv, const double X[], long nt, const long T[], const double lam[], const double mu[],
                   long cap, long Ki[], long Kj[], double Kv[], long *nnz, long *bad);

/* The same on quadratic tetrahedra ([P2, P2, P2], straight-sided: the
 * geometry from the vertices X, T): nn nodes, node[10 nt] each
 * tetrahedron's nodes in FreeFEM's order (ffc_p2_number: the vertices,
 * then the edges 01 02 03 12 13 23), dof 3 i + c of node i; the count
 * needed is 9 x (node pairs that share a tetrahedron, each node with
 * itself); FFC_ERR_INDEX also for a node outside [0, nn). */
int ffc_elastic_p2(long nv, const double X[], long nt, const long T[], long nn, const long node[],
                   const double lam[], const double mu[], long cap, long Ki[], long Kj[], double Kv[], long *nnz,
                   long *bad);

/* ------------------------------------------------ mass redistribution */
/* The interpolation T (n x n) of a redistributed mass M_red = T' M T for
 * contact dynamics: row i is e_i for a dof off the contact surfaces
 * (spread[i] == 0); a dof on them (spread[i] != 0) takes the mean of the
 * dofs off the surfaces that the mass matrix (triplets Mi, Mj, Mv [nm],
 * duplicates allowed) couples to it, weighted by |M_ij|.  Rows sum to 1
 * (total mass and linear momentum kept), T T = T, and M_red has no mass on
 * the surface dofs, which then follow the quasi-static balance of elastic
 * and contact forces: no contact chatter, and the trapezoidal rule keeps
 * the energy in persistent contact.  A surface dof coupled to no dof off
 * the surfaces (a body one element thick) keeps its row e_i: *kept counts
 * them.  T goes to the triplets (Ti, Tj, Tv)[cap], *nt of them (the count
 * needed, with FFC_ERR_CAPACITY; at most n + nm).  Work: wsum[n]. */
int ffc_mass_spread(long n, long nm, const long Mi[], const long Mj[], const double Mv[],
                    const double spread[], long cap, long Ti[], long Tj[], double Tv[], long *nt,
                    long *kept, double wsum[]);

/* ------------------------------------------------- quadratic tetrahedra */
/* Numbers the nodes of P2 tetrahedra T[nt*4] (nv vertices) as FreeFEM
 * numbers scalar P2 degrees of freedom: element by element, the 4 vertices
 * then the edges (0,1), (0,2), (0,3), (1,2), (1,3), (2,3), each node at its
 * first appearance.  node[nt*10] receives the nodes of each element,
 * *nnodes their count.  (For [P2,P2,P2] the dof of node i, component c is
 * 3 i + c.) */
int ffc_p2_number(long nt, const long T[], long nv, long node[], long *nnodes);

/* Positions X2[nnodes*3] of the P2 nodes of straight-sided tetrahedra:
 * the vertices and the edge midpoints of X[nv*3]. */
int ffc_p2_positions(long nt, const long T[], const long node[], const double X[],
                     long nnodes, double X2[]);

/* The 6 nodes of the face (face[3], vertex numbers, in facet order) of the
 * tetrahedron T4 with nodes node10: the 3 vertex nodes, then the mid-edge
 * nodes of edges 0-1, 1-2, 2-0 of the face. */
int ffc_p2_face(const long T4[4], const long node10[10], const long face[3], long out[6]);

#ifdef __cplusplus
}
#endif
#endif /* FFC_H */
