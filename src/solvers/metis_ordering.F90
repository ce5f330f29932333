!> Nested-dissection fill-reducing ordering of a sparse symmetric pattern by
!! METIS (`METIS_NodeND`), for the sparse direct solvers that take a user
!! ordering (MUMPS: ICNTL(7) = 1, PERM_IN).
!!
!! The binding is built when CMake finds METIS 5 (Debian: libmetis-dev) and
!! defines KONTAKT2D_HAVE_METIS; without it `metis_available()` is false and
!! `nested_dissection` fails with a status, so that the caller falls back to
!! its own ordering.  METIS's integer type idx_t is the 32-bit C int of
!! Debian's build (IDXTYPEWIDTH = 32 in metis.h), i.e. c_int here; the
!! options are METIS's defaults (a fixed random seed: the ordering is the
!! same from run to run), so that results are reproducible.
!!
!! Ref: G. Karypis, V. Kumar, "A fast and high quality multilevel scheme for
!!      partitioning irregular graphs", SIAM J. Sci. Comput. 20 (1998)
!!      359-392; G. Karypis, METIS 5.1.0 manual (2013), sec. 5.5
!!      (METIS_NodeND: perm, iperm; "row i of A is row iperm[i] of A'").
module metis_ordering
   use, intrinsic :: iso_c_binding, only: c_int, c_ptr, c_null_ptr
   use errors, only: status_t, STAT_SOLVER
   use strings, only: itoa
   implicit none
   private
   public :: metis_available, nested_dissection

#ifdef KONTAKT2D_HAVE_METIS
   !> METIS_OK of metis.h.
   integer(c_int), parameter :: METIS_OK = 1

   interface
      !> int METIS_NodeND(idx_t *nvtxs, idx_t *xadj, idx_t *adjncy, idx_t *vwgt,
      !!                  idx_t *options, idx_t *perm, idx_t *iperm)
      integer(c_int) function metis_nodend(nvtxs, xadj, adjncy, vwgt, options, perm, iperm) &
         bind(c, name='METIS_NodeND')
         import :: c_int, c_ptr
         integer(c_int), intent(in) :: nvtxs
         integer(c_int), intent(in) :: xadj(*), adjncy(*)
         type(c_ptr), value :: vwgt, options
         integer(c_int), intent(out) :: perm(*), iperm(*)
      end function metis_nodend
   end interface
#endif

contains

   !> True when this build has METIS.
   pure logical function metis_available()
#ifdef KONTAKT2D_HAVE_METIS
      metis_available = .true.
#else
      metis_available = .false.
#endif
   end function metis_available

   !> Nested-dissection ordering of the graph (xadj, adjncy): position(i) is
   !! the place of vertex i in the elimination order (a permutation of 1..n).
   !! The graph is 1-based CSR, symmetric (every edge listed at both ends),
   !! without self loops.  STAT_SOLVER when METIS is not built in or fails.
   subroutine nested_dissection(n, xadj, adjncy, position, status)
      integer, intent(in) :: n                  !! vertices
      integer, intent(in) :: xadj(:)            !! (n+1) 1-based row pointers
      integer, intent(in) :: adjncy(:)          !! neighbours of each vertex
      integer, intent(out) :: position(:)       !! (n) place of each vertex in the order, 1..n
      type(status_t), intent(inout) :: status
#ifdef KONTAKT2D_HAVE_METIS
      integer(c_int), allocatable :: x0(:), a0(:), perm(:), iperm(:)
      integer(c_int) :: nv, rc
      integer :: ne
      if (n <= 0) return
      if (n == 1) then
         position(1) = 1
         return
      end if
      ne = xadj(n + 1) - 1
      ! METIS numbers from 0 by default
      x0 = int(xadj(1:n + 1) - 1, c_int)
      allocate (a0(max(ne, 1)), perm(n), iperm(n))
      a0(1:ne) = int(adjncy(1:ne) - 1, c_int)
      nv = int(n, c_int)
      rc = metis_nodend(nv, x0, a0, c_null_ptr, c_null_ptr, perm, iperm)
      if (rc /= METIS_OK) then
         call status%set(STAT_SOLVER, 'METIS_NodeND failed (return code '//itoa(int(rc))// &
                         ') on a graph of '// &
                         itoa(n)//' vertices')
         return
      end if
      position(1:n) = int(iperm, kind(position)) + 1
#else
      position(1:max(n, 0)) = 0
      if (size(xadj) + size(adjncy) < 0) return     ! (the graph is not read in this build)
      call status%set(STAT_SOLVER, 'this build has no METIS (Debian: libmetis-dev)')
#endif
   end subroutine nested_dissection
end module metis_ordering
