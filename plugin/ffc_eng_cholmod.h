/* ffc_eng_cholmod.h: the CHOLMOD engine's state, shared by its two files
 * (ffc_eng_cholmod.c: one process; ffc_eng_split.c: the ranks of a
 * machine factorizing and solving by subtrees); internal. */
#ifndef FFC_ENG_CHOLMOD_H
#define FFC_ENG_CHOLMOD_H

#include <suitesparse/cholmod.h>

#include "ffc_engine.h"

enum { FFC__BLOCK = 128 };  /* inverse columns per block back-solve (128 against 64: the same at 44k dofs,
                               about 10 % less at 141k) */

typedef struct {
    ffc__engine base;
    ffc__ranks *rk;            /* the ranks holding the factor, each all of it (size 1: one process) */
    int started;               /* cholmod_start called */
    cholmod_common cc;
    cholmod_factor *L;         /* NULL until the first analysis */
    cholmod_dense *B, *X, *Y, *E;       /* one right-hand side and solve2's work */
    cholmod_dense *Bb, *Xb, *Yb, *Eb;   /* a block of FFC__BLOCK right-hand sides (Bb zero between uses) */
    /* the ranks of this machine (rk->size > 1): they factorize by subtrees, each into its own L */
    int ncomm;                 /* their communicator (Fortran handle; valid when nsize > 1) */
    int nrank, nsize;          /* this rank among them, their count */
    int split;                 /* the ranks that made the last factor's subtrees (0: none) */
    signed char *spart;        /* [nsuper] each supernode's set (-1: above the sets); NULL: no split. The
                                  single solves are split the same way (ffc__chol_split_solve) */
    double *sx;                /* [n + sbelow + n + split * ntop] the split solve's work (NULL until used) */
    long *scnt;                /* [nsize] its counts of values per rank */
    long sbelow, ntop;         /* the most rows below a supernode's diagonal block; the columns above the sets */
    /* the pruned solves of a supernodal factor (made with the factor) */
    int prune;                 /* 1: the inverse by pruned solves when L is supernodal (default) */
    int force_super;           /* 1: a supernodal L whatever its size (test hook; 0: CHOLMOD chooses) */
    int *ipm;                  /* [n] position of each dof in L's order (the inverse of L->Perm) */
    int *sn;                   /* [n] the supernode of each of L's columns */
    int *spar;                 /* [nsuper] each supernode's parent in the supernodal elimination tree, or -1 */
    int *sroot;                /* [nsuper] the root of each supernode's tree (one tree per part of the matrix
                                  that nothing couples: each body, before contact) */
    unsigned char *smark;      /* [nsuper] work: 1 on the supernodes a solve visits */
    unsigned char *tmark;      /* [nsuper] work: 1 on the roots of the trees a block of columns lies in */
    double *sw;                /* [swcap] work: a supernode's rows below its diagonal block x FFC__BLOCK */
    long swcap;
    double pshare;             /* the share of L's entries the last pruned backward solves visited */
    double min_rcond;          /* a factor of estimated reciprocal condition below it is singular (1e-12;
                                  0: only a failed factorization is, for matrices with tgv rows) */
} ffc__chol;

/* ffc_eng_split.c */
/* this machine's ranks found (a communicator of their own when more than one) */
void ffc__chol_node_init(ffc__chol *c);
void ffc__chol_node_free(ffc__chol *c);
/* the numeric factorization of A (lower, packed) into the analysed c->L
 * by the machine's ranks, each a set of subtrees (see the file) */
int ffc__chol_numeric_on_node(ffc__chol *c, cholmod_sparse *A);
/* y = A^-1 rhs, the machine's ranks each solving its set's subtrees */
int ffc__chol_split_solve(ffc__chol *c, const double rhs[], double y[]);
/* the split's work dropped */
void ffc__chol_split_free(ffc__chol *c);

/* ffc_eng_cholmod.c */
/* c->base.info->rcond of the numeric c->L; FFC_ERR_SINGULAR below c->min_rcond */
int ffc__chol_conditioned(ffc__chol *c);
/* the numeric factorization of A into the analysed c->L on this rank alone */
int ffc__chol_numeric(ffc__chol *c, cholmod_sparse *A);
/* ok on every rank holding the factor (a collective call; ok itself alone) */
int ffc__chol_all(const ffc__chol *c, int ok);

#endif
