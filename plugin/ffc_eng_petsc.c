/* ffc_eng_petsc.c: the PETSc engine: GMRES right-preconditioned by
 * algebraic multigrid (GAMG with the rigid-body modes, or BoomerAMG) or a
 * direct LU by MUMPS, the rows shared out over the ranks of a communicator
 * (built with -DFFC_PETSC; without it, FFC_ERR_UNAVAILABLE). */
#include <stdlib.h>

#include "ffc_engine.h"
#include "ffc_internal.h"

#ifdef FFC_PETSC

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <petscksp.h>

typedef struct {
    ffc__engine base;
    ffc_iterative opt;         /* the method (opt.xyz copied to xyz) */
    double *xyz;               /* [3 nv] the nodes' coordinates (NULL: none) */
    MPI_Comm comm;             /* the ranks that share the rows */
    int rank, size;
    PetscInt lo, hi;           /* this rank's rows [lo, hi) */
    Mat A;                     /* the matrix, its Dirichlet rows scaled (NULL before analyze) */
    KSP ksp;
    Vec b, x, xall;            /* right-hand side and solution (distributed), the solution on every rank */
    VecScatter toall;
    double *scale;             /* [n] each row's factor: 1 / its diagonal on a tgv row, else 1 */
    long *to;                  /* [n] PETSc's row of each dof (NULL: the same) */
    long *from;                /* [n] the dof of each PETSc row (NULL: the same) */
    long nb, nbcap;            /* the block's dofs (count), its capacity */
    long *block;               /* [nb] the dofs solved exactly after each multigrid cycle (ascending) */
    IS bis;                    /* this rank's share of them (NULL: no block) */
    Mat Abb;                   /* E' A E */
    KSP kb;                    /* its LU (MUMPS over the ranks) */
    ffc_iterative_info st;     /* what the solves did */
} ffc__pet;

/* 1: a PETSc error class that names a caller's mistake (an option from
 * PETSC_OPTIONS PETSc refuses, an unknown type, an unsupported
 * combination), not a failure of the numbers at hand */
static int refused(PetscErrorCode ierr)
{
    switch (ierr) {
    case PETSC_ERR_SUP: case PETSC_ERR_USER_INPUT: case PETSC_ERR_ARG_UNKNOWN_TYPE: case PETSC_ERR_ARG_WRONG:
    case PETSC_ERR_ARG_OUTOFRANGE: case PETSC_ERR_ARG_INCOMP: case PETSC_ERR_ARG_TYPENOTSET: case PETSC_ERR_ARG_SIZ:
    case PETSC_ERR_ARG_IDN: case PETSC_ERR_ARG_NOTSAMETYPE: case PETSC_ERR_ARG_NOTSAMECOMM:
    case PETSC_ERR_ARG_WRONGSTATE: case PETSC_ERR_ARG_NULL: case PETSC_ERR_ARG_BADPTR: case PETSC_ERR_ARG_CORRUPT:
        return 1;
    default:
        return 0;
    }
}

/* a PETSc error turned into a status with its message: out of memory; a
 * zero pivot (singular); FFC_ERR_VALUE where PETSc refused what it was
 * asked (refused: the caller's to mend, an error); else FFC_ERR_NOCONV,
 * as for a Krylov solve that stopped short (a failure of this matrix,
 * the step cut and tried again smaller), the message kept */
static int pfail(ffc__pet *p, PetscErrorCode ierr, const char *what)
{
    const char *text = NULL;
    char *detail = NULL;   /* (the error's own words, naming the value: preferred to the class's text) */
    PetscErrorMessage(ierr, &text, &detail);
    const int st = ierr == PETSC_ERR_MEM                                          ? FFC_ERR_MEMORY
                   : ierr == PETSC_ERR_MAT_LU_ZRPVT || ierr == PETSC_ERR_MAT_CH_ZRPVT ? FFC_ERR_SINGULAR
                   : refused(ierr)                                                 ? FFC_ERR_VALUE
                                                                                   : FFC_ERR_NOCONV;
    return ffc__engine_fail(&p->base, st, FFC_AT_COUNT, p->base.n, "PETSc: %s: %s (error %d)", what,
                            detail && *detail ? detail : text ? text : "unknown", (int)ierr);
}
#define TRY(call, what)                                  \
    do {                                                 \
        PetscErrorCode e_ = (call);                      \
        if (e_) return pfail(p, e_, what);               \
    } while (0)

static int pet_agree(const ffc__engine *e, int ok)
{
    const ffc__pet *p = (const ffc__pet *)e;
    int all = ok;
    if (p->size > 1) MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, p->comm);
    return all;
}

static void drop_solver(ffc__pet *p)
{
    if (p->ksp) KSPDestroy(&p->ksp);
    if (p->kb) KSPDestroy(&p->kb);
    if (p->Abb) MatDestroy(&p->Abb);
    if (p->bis) ISDestroy(&p->bis);
    p->base.factored = 0;
}

static void pet_release(ffc__engine *e) { drop_solver((ffc__pet *)e); }

static void drop_all(ffc__pet *p)
{
    drop_solver(p);
    if (p->toall) VecScatterDestroy(&p->toall);
    if (p->A) MatDestroy(&p->A);
    if (p->b) VecDestroy(&p->b);
    if (p->x) VecDestroy(&p->x);
    if (p->xall) VecDestroy(&p->xall);
    free(p->scale);
    free(p->to);
    free(p->from);
    p->scale = NULL;
    p->to = p->from = NULL;
    p->base.n = 0;
}

static void pet_free(ffc__engine *e)
{
    ffc__pet *p = (ffc__pet *)e;
    drop_all(p);
    free(p->xyz);
    free(p->block);
    free(p);
}

/* Recursive coordinate bisection: the nodes idx[n] reordered so that
 * parts consecutive runs of them, of sizes n k / parts, are compact in
 * space (each run cut off along the longest side of its box at the
 * count that its share of the parts asks for). */
static int cmp_key(const void *a, const void *b)
{
    const double x = ((const double *)a)[0], y = ((const double *)b)[0];
    return (x > y) - (x < y);
}
static void rcb(const double *xyz, long *idx, long n, int parts, double *work)
{
    if (parts <= 1 || n < 2) return;
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (long k = 0; k < n; k++)
        for (int c = 0; c < 3; c++) {
            const double x = xyz[3 * idx[k] + c];
            if (x < lo[c]) lo[c] = x;
            if (x > hi[c]) hi[c] = x;
        }
    int ax = 0;
    for (int c = 1; c < 3; c++)
        if (hi[c] - lo[c] > hi[ax] - lo[ax]) ax = c;
    for (long k = 0; k < n; k++) { /* (key, node) pairs, sorted by key */
        work[2 * k] = xyz[3 * idx[k] + ax];
        work[2 * k + 1] = (double)idx[k];
    }
    qsort(work, (size_t)n, 2 * sizeof *work, cmp_key);
    for (long k = 0; k < n; k++) idx[k] = (long)work[2 * k + 1];
    const int left = parts / 2;
    const long cut = n * left / parts;
    rcb(xyz, idx, cut, left, work);
    rcb(xyz, idx + cut, n - cut, parts - left, work);
}

/* On several ranks with the nodes known: PETSc's rows numbered so that
 * each rank's contiguous share is a compact piece of the bodies (a
 * node's three dofs together), so that the multigrid's aggregates and
 * the ranks' couplings follow the mesh; p->to / p->from map dofs to rows
 * and back. (FreeFEM's node numbering scatters a share over the whole
 * mesh: on 2 ranks GAMG took 3x the iterations of one.) */
static int renumber(ffc__pet *p, long n)
{
    if (p->size < 2 || !p->xyz || n != 3 * p->opt.nv) return FFC_OK;
    const long nv = p->opt.nv;
    long *idx = malloc((size_t)nv * sizeof *idx);
    double *work = malloc((size_t)(2 * nv) * sizeof *work);
    p->to = malloc((size_t)n * sizeof *p->to);
    p->from = malloc((size_t)n * sizeof *p->from);
    if (!idx || !work || !p->to || !p->from) {
        free(idx); free(work);
        return ffc__engine_fail(&p->base, FFC_ERR_MEMORY, FFC_AT_COUNT, n, "PETSc: out of memory for the renumbering");
    }
    for (long v = 0; v < nv; v++) idx[v] = v;
    rcb(p->xyz, idx, nv, p->size, work);
    for (long r = 0; r < nv; r++)
        for (int c = 0; c < 3; c++) {
            p->from[3 * r + c] = 3 * idx[r] + c;
            p->to[3 * idx[r] + c] = 3 * r + c;
        }
    free(idx); free(work);
    return FFC_OK;
}
#define ROW(p, i) ((p)->to ? (p)->to[i] : (i))
#define DOF(p, r) ((p)->from ? (p)->from[r] : (r))

/* The rigid-body modes of the nodes as GAMG's near-null space (a
 * displacement field: n = 3 nv, dof 3 i + c component c of node i), set
 * on A once per pattern (its values change, the nodes do not). */
static int near_null(ffc__pet *p)
{
    if (!p->xyz || p->base.n != 3 * p->opt.nv) return FFC_OK;
    Vec c;
    MatNullSpace ns;
    TRY(MatCreateVecs(p->A, &c, NULL), "the nodes' coordinates");
    PetscScalar *a;
    TRY(VecGetArray(c, &a), "the nodes' coordinates");
    for (PetscInt i = p->lo; i < p->hi; i++) a[i - p->lo] = p->xyz[DOF(p, i)];
    TRY(VecRestoreArray(c, &a), "the nodes' coordinates");
    TRY(MatNullSpaceCreateRigidBody(c, &ns), "the rigid-body modes");
    TRY(MatSetNearNullSpace(p->A, ns), "the rigid-body modes");
    MatNullSpaceDestroy(&ns);
    VecDestroy(&c);
    return FFC_OK;
}

/* Rows are shared out in blocks of three (a node's dofs) when n is a
 * multiple of three, so that the block size and the rigid-body modes
 * hold on every rank. */
static int pet_analyze(ffc__engine *e, const ffc__tri *T)
{
    ffc__pet *p = (ffc__pet *)e;
    drop_all(p);
    const PetscInt n = (PetscInt)T->n, bs = n % 3 == 0 ? 3 : 1, nb = n / bs;
    int rs = renumber(p, T->n);
    if (rs) return rs;
    p->lo = (PetscInt)((long)nb * p->rank / p->size) * bs;
    p->hi = (PetscInt)((long)nb * (p->rank + 1) / p->size) * bs;
    const PetscInt m = p->hi - p->lo;
    PetscInt *dn = calloc((size_t)m + 1, sizeof *dn), *on = calloc((size_t)m + 1, sizeof *on);
    p->scale = malloc((size_t)n * sizeof *p->scale);
    if (!dn || !on || !p->scale) {
        free(dn); free(on);
        return ffc__engine_fail(e, FFC_ERR_MEMORY, FFC_AT_COUNT, n, "PETSc: out of memory for the pattern (order %ld)",
                                (long)n);
    }
    /* (the pattern's entries are distinct: one count each; a symmetric
     * pattern's lower triangle stands for both) */
    for (long k = 0; k < T->nz; k++)
        for (int t = 0; t < 1 + (T->sym && T->i[k] != T->j[k]); t++) {
            const PetscInt r = ROW(p, t ? T->j[k] : T->i[k]), c = ROW(p, t ? T->i[k] : T->j[k]);
            if (r < p->lo || r >= p->hi) continue;
            if (c >= p->lo && c < p->hi) dn[r - p->lo]++;
            else on[r - p->lo]++;
        }
    for (PetscInt r = 0; r < m; r++) {
        if (dn[r] > m) dn[r] = m;
        if (on[r] > n - m) on[r] = n - m;
    }
    e->n = n;
    PetscErrorCode ierr = MatCreate(p->comm, &p->A);
    if (!ierr) ierr = MatSetSizes(p->A, m, m, n, n);
    if (!ierr) ierr = MatSetType(p->A, MATAIJ);
    if (!ierr) ierr = MatSetBlockSize(p->A, bs);
    if (!ierr) ierr = MatSeqAIJSetPreallocation(p->A, 0, dn);
    if (!ierr) ierr = MatMPIAIJSetPreallocation(p->A, 0, dn, 0, on);
    if (!ierr) ierr = MatSetOption(p->A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE);
    free(dn); free(on);
    if (!ierr) ierr = MatCreateVecs(p->A, &p->x, &p->b);
    if (!ierr) ierr = VecScatterCreateToAll(p->x, &p->toall, &p->xall);
    if (ierr) return pfail(p, ierr, "the matrix's layout");
    return near_null(p);
}

static int cmp_row(const void *a, const void *b)
{
    const PetscInt x = *(const PetscInt *)a, y = *(const PetscInt *)b;
    return (x > y) - (x < y);
}

/* z = E (E' A E)^-1 E' r: the block's exact solve, zero elsewhere */
static PetscErrorCode block_apply(PC pc, Vec r, Vec z)
{
    void *ctx = NULL;
    PetscCall(PCShellGetContext(pc, &ctx));
    ffc__pet *p = ctx;
    Vec rb, zb;
    PetscCall(VecSet(z, 0.0));
    PetscCall(VecGetSubVector(r, p->bis, &rb));
    PetscCall(VecGetSubVector(z, p->bis, &zb));
    PetscCall(KSPSolve(p->kb, rb, zb));
    PetscCall(VecRestoreSubVector(r, p->bis, &rb));
    PetscCall(VecRestoreSubVector(z, p->bis, &zb));
    return 0;
}

/* The multigrid of opt.pc on pc */
static int multigrid(ffc__pet *p, PC pc)
{
    if (p->opt.pc == FFC_PC_HYPRE) {
        TRY(PCSetType(pc, PCHYPRE), "BoomerAMG");
        TRY(PCHYPRESetType(pc, "boomeramg"), "BoomerAMG");
    } else {
        TRY(PCSetType(pc, PCGAMG), "GAMG");
    }
    return FFC_OK;
}

/* Formulation: the preconditioner of K + Kc where a block B of dofs is
 * given (those the contact couples): one multigrid cycle M, then the
 * block solved exactly on the residual left,
 *   z = M^-1 r,  z += E (E' A E)^-1 E' (r - A z),
 * E the columns of the identity on B (its rows on their ranks, the LU of
 * E' A E by MUMPS over them all: the same block on any number of
 * ranks). The penalty's springs
 * make A's modes on B stiff and anisotropic (normal against tangential),
 * which aggregation's smoothers do not reach; on B they are solved
 * outright, and the multigrid keeps the bulk's smooth modes. */
static int make_solver(ffc__pet *p)
{
    PC pc;
    TRY(KSPCreate(p->comm, &p->ksp), "the Krylov solver");
    TRY(KSPGetPC(p->ksp, &pc), "the preconditioner");
    if (p->opt.pc == FFC_PC_MUMPS) {
        TRY(KSPSetType(p->ksp, KSPPREONLY), "the direct solver");
        TRY(PCSetType(pc, PCLU), "the direct solver");
        TRY(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "MUMPS through PETSc");
    } else {
        TRY(KSPSetType(p->ksp, KSPGMRES), "GMRES");
        TRY(KSPGMRESSetRestart(p->ksp, 100), "GMRES");
        TRY(KSPSetPCSide(p->ksp, PC_RIGHT), "GMRES");
        TRY(KSPSetNormType(p->ksp, KSP_NORM_UNPRECONDITIONED), "GMRES");
        TRY(KSPSetTolerances(p->ksp, p->opt.rtol, 0.0, 1e10, (PetscInt)p->opt.maxit), "GMRES");
        /* this rank's rows of the block, ascending */
        PetscInt *rows = malloc((size_t)(p->nb > 0 ? p->nb : 1) * sizeof *rows), m = 0;
        if (!rows) return ffc__engine_fail(&p->base, FFC_ERR_MEMORY, FFC_AT_COUNT, p->nb, "PETSc: out of memory for the block");
        for (long k = 0; k < p->nb; k++) {
            const long r = ROW(p, p->block[k]);
            if (r >= p->lo && r < p->hi) rows[m++] = (PetscInt)r;
        }
        qsort(rows, (size_t)m, sizeof *rows, cmp_row);
        long mine = m, all = m;
        if (p->size > 1) MPI_Allreduce(&mine, &all, 1, MPI_LONG, MPI_SUM, p->comm);
        if (all == 0) {
            free(rows);
            int st = multigrid(p, pc);
            if (st) return st;
        } else {
            PC mg, bj;
            PetscErrorCode ierr = ISCreateGeneral(p->comm, m, rows, PETSC_COPY_VALUES, &p->bis);
            free(rows);
            if (ierr) return pfail(p, ierr, "the block");
            TRY(PCSetType(pc, PCCOMPOSITE), "the composite preconditioner");
            TRY(PCCompositeSetType(pc, PC_COMPOSITE_MULTIPLICATIVE), "the composite preconditioner");
            TRY(PCCompositeAddPCType(pc, PCGAMG), "the composite preconditioner");
            TRY(PCCompositeAddPCType(pc, PCSHELL), "the composite preconditioner");
            TRY(PCCompositeGetPC(pc, 0, &mg), "the composite preconditioner");
            TRY(PCCompositeGetPC(pc, 1, &bj), "the composite preconditioner");
            int st = multigrid(p, mg);
            if (st) return st;
            TRY(PCShellSetContext(bj, p), "the block");
            TRY(PCShellSetApply(bj, block_apply), "the block");
            TRY(PCShellSetName(bj, "the contact's block, solved exactly"), "the block");
        }
    }
    /* (PETSc's own options, from PETSC_OPTIONS, last: -ksp_monitor, a
     * smoother, a threshold) */
    TRY(KSPSetFromOptions(p->ksp), "PETSC_OPTIONS");
    return FFC_OK;
}

/* the block's LU: E' A E taken out of A (its rows on their ranks) and
 * factorized by MUMPS over the same ranks (after A's assembly) */
static int block_setup(ffc__pet *p)
{
    if (!p->bis) return FFC_OK;
    PC pc;
    TRY(MatCreateSubMatrix(p->A, p->bis, p->bis, MAT_INITIAL_MATRIX, &p->Abb), "the block");
    TRY(KSPCreate(p->comm, &p->kb), "the block's LU");
    TRY(KSPSetOptionsPrefix(p->kb, "ffc_block_"), "the block's LU");
    TRY(KSPSetOperators(p->kb, p->Abb, p->Abb), "the block's LU");
    TRY(KSPSetType(p->kb, KSPPREONLY), "the block's LU");
    TRY(KSPGetPC(p->kb, &pc), "the block's LU");
    TRY(PCSetType(pc, PCLU), "the block's LU");
    TRY(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "the block's LU");
    TRY(KSPSetUp(p->kb), "the block's LU");
    return FFC_OK;
}

/* Formulation: the matrix handed over is A with each Dirichlet row (its
 * diagonal a tgv, >= 1e20) divided by that diagonal, so that the row
 * reads x_i = g_i and weighs in the residual's norm as the displacement
 * it imposes (the right-hand side is scaled alike in solve); the
 * preconditioner is built here, once per matrix: the multigrid
 * hierarchy, or MUMPS's factors. */
static int pet_factorize(ffc__engine *e, const ffc__tri *T)
{
    ffc__pet *p = (ffc__pet *)e;
    const double t0 = ffc__seconds();
    for (long i = 0; i < T->n; i++) p->scale[i] = 0.0;
    for (long k = 0; k < T->nz; k++)
        if (T->i[k] == T->j[k]) p->scale[T->i[k]] += T->v[k];
    for (long i = 0; i < T->n; i++) p->scale[i] = fabs(p->scale[i]) >= 1e20 ? 1.0 / fabs(p->scale[i]) : 1.0;
    TRY(MatZeroEntries(p->A), "the matrix's values");
    for (long k = 0; k < T->nz; k++)
        for (int t = 0; t < 1 + (T->sym && T->i[k] != T->j[k]); t++) {
            const long i = t ? T->j[k] : T->i[k];
            const PetscInt r = ROW(p, i), c = ROW(p, t ? T->i[k] : T->j[k]);
            if (r < p->lo || r >= p->hi) continue;
            const PetscScalar v = T->v[k] * p->scale[i];
            TRY(MatSetValues(p->A, 1, &r, 1, &c, &v, ADD_VALUES), "the matrix's values");
        }
    TRY(MatAssemblyBegin(p->A, MAT_FINAL_ASSEMBLY), "the matrix's assembly");
    TRY(MatAssemblyEnd(p->A, MAT_FINAL_ASSEMBLY), "the matrix's assembly");
    /* (made again for each matrix: the block changes with the contact) */
    drop_solver(p);
    int st = make_solver(p);
    if (st) return st;
    TRY(KSPSetOperators(p->ksp, p->A, p->A), "the operators");
    PetscErrorCode ierr = KSPSetUp(p->ksp);
    if (!ierr) {
        PC pc;
        KSPGetPC(p->ksp, &pc);
        ierr = PCSetUp(pc);
    }
    if (!ierr && (st = block_setup(p))) { drop_solver(p); return st; }
    if (ierr) {
        drop_solver(p);
        return pfail(p, ierr, p->opt.pc == FFC_PC_MUMPS ? "MUMPS's factorization" : "the preconditioner's set-up");
    }
    p->st.setups++;
    p->st.t_setup += ffc__seconds() - t0;
    e->factored = 1;
    return FFC_OK;
}

static int pet_solve(ffc__engine *e, const double b[], double x[])
{
    ffc__pet *p = (ffc__pet *)e;
    if (!e->factored) return ffc__engine_fail(e, FFC_ERR_VALUE, FFC_AT_COUNT, e->n, "PETSc: solve before a set-up");
    const double t0 = ffc__seconds();
    PetscScalar *a;
    TRY(VecGetArray(p->b, &a), "the right-hand side");
    for (PetscInt i = p->lo; i < p->hi; i++) a[i - p->lo] = b[DOF(p, i)] * p->scale[DOF(p, i)];
    TRY(VecRestoreArray(p->b, &a), "the right-hand side");
    TRY(KSPSolve(p->ksp, p->b, p->x), "the solve");
    KSPConvergedReason why;
    PetscInt its = 0;
    KSPGetConvergedReason(p->ksp, &why);
    KSPGetIterationNumber(p->ksp, &its);
    p->st.solves++;
    p->st.iterations += its;
    p->st.last_iterations = its;
    p->st.t_solve += ffc__seconds() - t0;
    if (why < 0) {
        PetscReal rn = 0, bn = 0;
        KSPGetResidualNorm(p->ksp, &rn);
        VecNorm(p->b, NORM_2, &bn);
        return ffc__engine_fail(e, FFC_ERR_NOCONV, FFC_AT_COUNT, its,
                                "PETSc: %s did not converge in %ld iterations (%s): residual %.3g of |b|, rtol %.3g",
                                p->opt.pc == FFC_PC_MUMPS ? "MUMPS" : "GMRES", (long)its, KSPConvergedReasons[why],
                                bn > 0 ? (double)(rn / bn) : 0.0, p->opt.rtol);
    }
    TRY(VecScatterBegin(p->toall, p->x, p->xall, INSERT_VALUES, SCATTER_FORWARD), "the solution's gathering");
    TRY(VecScatterEnd(p->toall, p->x, p->xall, INSERT_VALUES, SCATTER_FORWARD), "the solution's gathering");
    const PetscScalar *c;
    TRY(VecGetArrayRead(p->xall, &c), "the solution");
    for (long r = 0; r < e->n; r++) x[DOF(p, r)] = c[r];
    /* a Dirichlet row's value exactly (its row reads x_i = b_i / tgv to
     * within 1e-20 of its other terms), not to the Krylov tolerance: an
     * imposed value off by rtol would keep Newton's Dirichlet test from
     * passing */
    for (long i = 0; i < e->n; i++)
        if (p->scale[i] != 1.0) x[i] = b[i] * p->scale[i];
    TRY(VecRestoreArrayRead(p->xall, &c), "the solution");
    return FFC_OK;
}

static int pet_inverse(ffc__engine *e, long nc, long cols[], long nrows, const long rows[], ffc__inv_sink sink,
                       void *ctx)
{
    return ffc__inverse_by_solves(e, nc, cols, nrows, rows, sink, ctx);
}

static const ffc__engine_ops pet_ops = {"PETSc", pet_analyze, pet_factorize, pet_solve, pet_inverse, pet_agree,
                                        pet_release, pet_free};

int ffc__petsc_create(ffc_solve_info *info, const ffc_iterative *opt, ffc__engine **out)
{
    *out = NULL;
    PetscBool up = PETSC_FALSE;
    PetscInitialized(&up);
    if (!up) {
        /* PETSc leaves signals and errors to the caller: no handler of its
         * own, no message printed (each error is returned) */
        if (PetscOptionsSetValue(NULL, "-no_signal_handler", NULL)) return FFC_ERR_UNAVAILABLE;
        if (PetscInitializeNoArguments()) return FFC_ERR_UNAVAILABLE;
    }
    PetscPushErrorHandler(PetscReturnErrorHandler, NULL);
    ffc__pet *p = calloc(1, sizeof *p);
    if (!p) return FFC_ERR_MEMORY;
    p->base.op = &pet_ops;
    p->base.info = info;
    p->opt = *opt;
    p->opt.xyz = NULL;
    if (opt->xyz && opt->nv > 0) {
        p->xyz = malloc((size_t)(3 * opt->nv) * sizeof *p->xyz);
        if (!p->xyz) { free(p); return FFC_ERR_MEMORY; }
        memcpy(p->xyz, opt->xyz, (size_t)(3 * opt->nv) * sizeof *p->xyz);
    }
    p->comm = PETSC_COMM_SELF;
#ifdef FFC_MPI
    if (opt->shared) p->comm = MPI_Comm_f2c((MPI_Fint)opt->fcomm);
#endif
    MPI_Comm_rank(p->comm, &p->rank);
    MPI_Comm_size(p->comm, &p->size);
    info->ranks = p->size;
    *out = &p->base;
    return FFC_OK;
}

int ffc__petsc_info(const ffc__engine *e, ffc_iterative_info *out)
{
    *out = ((const ffc__pet *)e)->st;
    return FFC_OK;
}

int ffc__petsc_set_block(ffc__engine *e, long nb, const long dofs[])
{
    ffc__pet *p = (ffc__pet *)e;
    if (nb > p->nbcap) {
        long *b = realloc(p->block, (size_t)nb * sizeof *b);
        if (!b) return FFC_ERR_MEMORY;
        p->block = b;
        p->nbcap = nb;
    }
    if (nb > 0) memcpy(p->block, dofs, (size_t)nb * sizeof *dofs);
    p->nb = nb;
    return FFC_OK;
}

int ffc_has_petsc(void) { return 1; }

#else

int ffc__petsc_create(ffc_solve_info *info, const ffc_iterative *opt, ffc__engine **out)
{
    (void)info; (void)opt;
    *out = NULL;
    return FFC_ERR_UNAVAILABLE;
}

int ffc__petsc_info(const ffc__engine *e, ffc_iterative_info *out)
{
    (void)e; (void)out;
    return FFC_ERR_UNAVAILABLE;
}

int ffc__petsc_set_block(ffc__engine *e, long nb, const long dofs[])
{
    (void)e; (void)nb; (void)dofs;
    return FFC_ERR_UNAVAILABLE;
}

int ffc_has_petsc(void) { return 0; }

#endif
