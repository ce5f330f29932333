!> The process's heap policy for solvers that allocate and free large arrays
!! at every factorization (MUMPS: its factors and work arrays, about 200 MB
!! at 1e5 equations, allocated anew by every JOB = 2).
!!
!! glibc serves allocations above its mmap threshold by mmap and returns them
!! to the system when freed; every new factorization then faults the pages of
!! its arrays in again (the kernel zeroes each page: system CPU time).  The
!! benchmark of many contact pairs (3 001 pairs on 1.1e5 DOFs, 227
!! factorizations; docs/performance.md, "A kept factorization and the heap") spent
!! 9.4 s of its 68.7 s CPU there.  keep_freed_heap makes every allocation come
!! from the heap (no mmap) and keeps freed memory in it (no trimming), so that
!! the next factorization reuses the same pages: the same peak (the largest
!! factorization's arrays), 0.16 s of system time.  A no-op without glibc's
!! mallopt (KONTAKT2D_HAVE_MALLOPT, set by CMake).
module heap_policy
   use, intrinsic :: iso_c_binding, only: c_int
   implicit none
   private
   public :: keep_freed_heap

#ifdef KONTAKT2D_HAVE_MALLOPT
   !> glibc's <malloc.h> parameters of mallopt.
   integer(c_int), parameter :: M_TRIM_THRESHOLD = -1_c_int, M_MMAP_MAX = -4_c_int

   interface
      integer(c_int) function mallopt(param, value) bind(c, name='mallopt')
         import :: c_int
         integer(c_int), value :: param, value
      end function mallopt
   end interface
#endif

   logical :: done = .false.

contains

   !> Keep freed memory in the heap from now on (once per process).
   subroutine keep_freed_heap()
#ifdef KONTAKT2D_HAVE_MALLOPT
      integer(c_int) :: ok
      if (done) return
      done = .true.
      ok = mallopt(M_MMAP_MAX, 0_c_int)
      ok = mallopt(M_TRIM_THRESHOLD, huge(0_c_int))
#else
      done = .true.
#endif
   end subroutine keep_freed_heap
end module heap_policy
