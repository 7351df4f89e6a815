/* ffc_mpi.c: the ranks of MPI_COMM_WORLD, reductions and gathers over them,
 * and this process's peak memory (a build without -DFFC_MPI is one rank). */
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "ffc.h"
#include "ffc_internal.h"

/* ffc_mpi_gather_triplets's arguments on this rank (*total = 0 first) */
static int gather_args(long nt, const long Ti[], const long Tj[], const double Tv[], long cap, const long Oi[],
                       const long Oj[], const double Ov[], long *total)
{
    if (!total) return FFC_ERR_NULL;
    *total = 0;
    if (nt < 0 || cap < 0) return FFC_ERR_SIZE;
    if ((nt > 0 && (!Ti || !Tj || !Tv)) || (cap > 0 && (!Oi || !Oj || !Ov))) return FFC_ERR_NULL;
    return FFC_OK;
}

/* one rank: the triplets copied (ffc_mpi_gather_triplets) */
static int gather_one(long nt, const long Ti[], const long Tj[], const double Tv[], long cap, long Oi[], long Oj[],
                      double Ov[], long *total)
{
    *total = nt;
    if (nt > cap) return FFC_ERR_CAPACITY;
    if (nt > 0) {
        memcpy(Oi, Ti, (size_t)nt * sizeof *Oi);
        memcpy(Oj, Tj, (size_t)nt * sizeof *Oj);
        memcpy(Ov, Tv, (size_t)nt * sizeof *Ov);
    }
    return FFC_OK;
}

#ifdef FFC_MPI
#include <mpi.h>

static int running(void)
{
    int init = 0, fin = 0;
    MPI_Initialized(&init);
    MPI_Finalized(&fin);
    return init && !fin;
}

int ffc_mpi_world(int *rank, int *size, int *fcomm)
{
    int r = 0, n = 1;
    if (running()) {
        MPI_Comm_rank(MPI_COMM_WORLD, &r);
        MPI_Comm_size(MPI_COMM_WORLD, &n);
    }
    if (rank) *rank = r;
    if (size) *size = n;
    if (fcomm) *fcomm = running() ? (int)MPI_Comm_c2f(MPI_COMM_WORLD) : 0;
    return FFC_OK;
}

int ffc_mpi_allreduce(double v[], long n, int op)
{
    if (n < 0 || n > 2147483647L) return FFC_ERR_SIZE;
    if (n > 0 && !v) return FFC_ERR_NULL;
    if (op < 0 || op > 2) return FFC_ERR_VALUE;
    if (!running() || n == 0) return FFC_OK;
    const MPI_Op o = op == 0 ? MPI_SUM : op == 1 ? MPI_MAX : MPI_MIN;
    /* reduced on rank 0, then broadcast: every rank gets the same bits (an
     * all-reduce may sum in a different order on each rank, and ranks that
     * differ in the last bit take different branches and wait for each
     * other in different collective calls) */
    int rank;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    int e = MPI_Reduce(rank == 0 ? MPI_IN_PLACE : v, rank == 0 ? v : NULL, (int)n, MPI_DOUBLE, o, 0, MPI_COMM_WORLD);
    if (e == MPI_SUCCESS) e = MPI_Bcast(v, (int)n, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    return e == MPI_SUCCESS ? FFC_OK : FFC_ERR_UNAVAILABLE;
}

/* the most negative of the ranks' statuses, on every rank (a rank that
 * returns early alone would leave the others waiting in a collective) */
static int agree_status(int st)
{
    int all = st;
    if (running()) MPI_Allreduce(&st, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    return all;
}

int ffc_mpi_gather_triplets(long nt, const long Ti[], const long Tj[], const double Tv[], long cap, long Oi[],
                            long Oj[], double Ov[], long *total)
{
    int st = gather_args(nt, Ti, Tj, Tv, cap, Oi, Oj, Ov, total);
    if (!st && nt > 2147483647L) st = FFC_ERR_SIZE;   /* (MPI's counts are int) */
    if ((st = agree_status(st))) return st;
    if (!running()) return gather_one(nt, Ti, Tj, Tv, cap, Oi, Oj, Ov, total);
    int size = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    long *cnt = malloc((size_t)size * sizeof *cnt);
    int *ci = malloc(2 * (size_t)size * sizeof *ci), *dsp = ci ? ci + size : NULL;
    st = agree_status(cnt && ci ? FFC_OK : FFC_ERR_MEMORY);
    if (!st && MPI_Allgather(&nt, 1, MPI_LONG, cnt, 1, MPI_LONG, MPI_COMM_WORLD) != MPI_SUCCESS)
        st = FFC_ERR_UNAVAILABLE;
    long all = 0;
    for (int r = 0; r < size && !st; r++) {
        if (all > 2147483647L - cnt[r]) st = FFC_ERR_SIZE;   /* (MPI's counts and offsets are int) */
        else { ci[r] = (int)cnt[r]; dsp[r] = (int)all; all += cnt[r]; }
    }
    if (!st) *total = all;
    if (!st && all > cap) st = FFC_ERR_CAPACITY;
    st = agree_status(st);
    if (!st && (MPI_Allgatherv(Ti, (int)nt, MPI_LONG, Oi, ci, dsp, MPI_LONG, MPI_COMM_WORLD) != MPI_SUCCESS ||
                MPI_Allgatherv(Tj, (int)nt, MPI_LONG, Oj, ci, dsp, MPI_LONG, MPI_COMM_WORLD) != MPI_SUCCESS ||
                MPI_Allgatherv(Tv, (int)nt, MPI_DOUBLE, Ov, ci, dsp, MPI_DOUBLE, MPI_COMM_WORLD) != MPI_SUCCESS))
        st = FFC_ERR_UNAVAILABLE;
    free(cnt);
    free(ci);
    return st;
}

int ffc_mpi_barrier(void)
{
    if (running()) MPI_Barrier(MPI_COMM_WORLD);
    return FFC_OK;
}

int ffc__mpi_ranks(int fcomm, int *rank, int *size)
{
    int r = 0, n = 1;
    if (running()) {
        const MPI_Comm c = MPI_Comm_f2c((MPI_Fint)fcomm);
        MPI_Comm_rank(c, &r);
        MPI_Comm_size(c, &n);
    }
    *rank = r;
    *size = n;
    return FFC_OK;
}

int ffc__mpi_min(int fcomm, int v)
{
    int all = v;
    if (running()) MPI_Allreduce(&v, &all, 1, MPI_INT, MPI_MIN, MPI_Comm_f2c((MPI_Fint)fcomm));
    return all;
}

int ffc__mpi_allgather(int fcomm, double buf[], const long count[])
{
    if (!running()) return FFC_OK;
    const MPI_Comm c = MPI_Comm_f2c((MPI_Fint)fcomm);
    int n = 1;
    MPI_Comm_size(c, &n);
    int *cnt = malloc(2 * (size_t)n * sizeof(int)), *dsp = cnt ? cnt + n : NULL;
    int ok = cnt != NULL;
    long off = 0;
    for (int r = 0; r < n && ok; r++) {
        ok = count[r] >= 0 && count[r] <= 2147483647L && off <= 2147483647L;
        if (ok) { cnt[r] = (int)count[r]; dsp[r] = (int)off; off += count[r]; }
    }
    int st = ffc__mpi_min(fcomm, ok) ? FFC_OK : FFC_ERR_SIZE;
    if (!st && MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, buf, cnt, dsp, MPI_DOUBLE, c) != MPI_SUCCESS)
        st = FFC_ERR_UNAVAILABLE;
    free(cnt);
    return st;
}

#else

int ffc_mpi_world(int *rank, int *size, int *fcomm)
{
    if (rank) *rank = 0;
    if (size) *size = 1;
    if (fcomm) *fcomm = 0;
    return FFC_OK;
}

int ffc_mpi_allreduce(double v[], long n, int op)
{
    if (n < 0) return FFC_ERR_SIZE;
    if (n > 0 && !v) return FFC_ERR_NULL;
    if (op < 0 || op > 2) return FFC_ERR_VALUE;
    return FFC_OK;
}

int ffc_mpi_gather_triplets(long nt, const long Ti[], const long Tj[], const double Tv[], long cap, long Oi[],
                            long Oj[], double Ov[], long *total)
{
    const int st = gather_args(nt, Ti, Tj, Tv, cap, Oi, Oj, Ov, total);
    return st ? st : gather_one(nt, Ti, Tj, Tv, cap, Oi, Oj, Ov, total);
}

int ffc_mpi_barrier(void) { return FFC_OK; }

int ffc__mpi_ranks(int fcomm, int *rank, int *size)
{
    (void)fcomm;
    *rank = 0;
    *size = 1;
    return FFC_OK;
}

int ffc__mpi_min(int fcomm, int v)
{
    (void)fcomm;
    return v;
}

int ffc__mpi_allgather(int fcomm, double buf[], const long count[])
{
    (void)fcomm; (void)buf; (void)count;
    return FFC_OK;
}

#endif

double ffc_peak_mb(void)
{
    struct rusage u;
    if (getrusage(RUSAGE_SELF, &u) != 0) return 0.0;
    return (double)u.ru_maxrss / 1024.0; /* Linux: kilobytes */
}
