/* ffc/status.h: status codes and their text, what an error's index counts, a failure's record; output sizes. */
#ifndef FFC_API_STATUS_H
#define FFC_API_STATUS_H

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
    FFC_ERR_CAPACITY = -8,        /* caller buffer too small (the size needed: "output sizes" below) */
    FFC_ERR_EMPTY = -9,           /* an empty surface or set */
    FFC_ERR_INDEX = -10,          /* a node index out of range */
    FFC_ERR_LABEL = -11,          /* a label that no boundary face carries */
    FFC_ERR_VALUE = -12,          /* a parameter outside its admissible range */
    FFC_ERR_MEMORY = -13,         /* allocation failed */
    FFC_ERR_INVERTED = -14,       /* a facet or tetrahedron turned inside out (normal reversed, det F <= 0) */
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
    FFC_AT_COUNT,      /* not a position: the count or size needed */
    FFC_AT_ELEMENT     /* a tetrahedron of the volume mesh */
} ffc_where;

/* A failure's record: its status, what failed (an index and what it
 * counts) and a message naming the cause (with sizes where they matter). */
typedef struct {
    int status;        /* a negative FFC_ERR_* (0: none) */
    ffc_where where;   /* what index counts */
    long index;        /* -1: none */
    char msg[200];     /* one line, no trailing newline ("" when none) */
} ffc_error;

/* -------------------------------------------------------- output sizes */
/* The sizes of outputs whose length the caller cannot know in advance:
 * the caller owns the buffer and passes its capacity cap (in the buffer's
 * entries: triplets, links, rows, points, motions); the function writes
 * the count it needs to its documented count output (*n, *nt, *ntrip,
 * *nrows, *nnz, *need, *nout, *total), both on success (the entries
 * written) and when the buffer is too short, which it reports with
 * FFC_ERR_CAPACITY (the buffer's contents are then unspecified); a call
 * with a capacity of at least that count and the same inputs does not
 * report it again.  Functions that follow it:
 *   ffc_mortar_search, ffc_mortar_pairs (*need), ffc_mortar_links (*lneed,
 *   *eneed), ffc_assemble (*ntrip), ffc_points_nodes (*n), ffc_nts_nodes
 *   (*need), ffc_nts_rows (*ntrip, *nrows), ffc_scene_assemble (*ntrip),
 *   ffc_scene_nts_rows (*ntrip, *nrows), ffc_scene_nts_solve (*nrows, the
 *   multipliers), ffc_scene_points, ffc_scene_multipliers (*n),
 *   ffc_rigid_free, ffc_scene_free_motions (*n), ffc_reduced_missing
 *   (*nout), ffc_elastic_p1, ffc_elastic_p2 (*nnz), ffc_mass_spread (*nt),
 *   ffc_mpi_gather_triplets (*total), ffc_tets_pattern (*nb).
 * Other functions say in their own comments how their outputs are sized. */

#ifdef __cplusplus
}
#endif
#endif /* FFC_API_STATUS_H */
