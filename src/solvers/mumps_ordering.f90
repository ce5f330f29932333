!> The fill-reducing orderings of the MUMPS solver (`mumps_solver`): their codes, the choice
!! of the default, their names in the listing, and METIS's nested dissection turned into
!! MUMPS's user ordering PERM_IN.
!!
!! Ordering.  AMD (MUMPS's own, ICNTL(7) = 0), or METIS's nested dissection
!! given as a user ordering (ICNTL(7) = 1, PERM_IN from `metis_ordering`;
!! Debian's MUMPS is not linked with METIS), or MUMPS's SCOTCH and PORD.
!! With a Schur complement MUMPS ignores ICNTL(7) = 0, 3, 4 (it orders by
!! AMD) but takes a user ordering (INFOG(7) = 1 after the analysis, checked
!! by the unit tests).  The Schur variables are given the last places, in
!! their order (MUMPS keeps them out of the elimination: last is where they
!! belong), and METIS orders the graph of the other equations.  Without METIS in the build the METIS
!! ordering falls back to AMD (`ordering_note` says so).  Which ordering is
!! the default, and why, is said at ORDERING_DEFAULT.
!!
!! Ref: MUMPS 5.5 Users' guide, ICNTL(7), INFOG(7), PERM_IN; P. R. Amestoy, T. A. Davis,
!!      I. S. Duff, "An approximate minimum degree ordering algorithm", SIAM J. Matrix Anal.
!!      Appl. 17 (1996) 886-905.
module mumps_ordering
   use errors, only: status_t
   use strings, only: itoa
   use metis_ordering, only: nested_dissection
   use mumps_pattern, only: reduced_graph
   implicit none
   private
   public :: ORDERING_AMD, ORDERING_SCOTCH, ORDERING_PORD, ORDERING_AUTO, ORDERING_METIS, &
             ORDERING_DEFAULT, METIS_MIN_NEQ
   public :: choose_ordering, ordering_text, metis_perm_in

   !> Fill-reducing orderings of MUMPS (ICNTL(7)).  AMD: deterministic and
   !! the cheapest analysis (0.3 s at 3e5 equations), the default for one
   !! factorization.  PORD stops the whole process (`exit`) on a graph it
   !! cannot split (a dense one: "no valid number of stages in
   !! multisector", met here on a 3-equation system), and SCOTCH's orderings
   !! differ from run to run (threads), so that results would not be
   !! bit-reproducible: both are available, never the default.
   integer, parameter :: ORDERING_AMD = 0, ORDERING_SCOTCH = 3, ORDERING_PORD = 4, ORDERING_AUTO = 7
   !> METIS's nested dissection (`metis_ordering`) given to MUMPS as a user
   !! ordering (ICNTL(7) = 1, PERM_IN); the value is MUMPS's INFOG(7) code
   !! for METIS.
   integer, parameter :: ORDERING_METIS = 5
   !> The default ordering (the value of `ordering` until it is set): AMD,
   !! but METIS when the pattern will be factorized many times
   !! (`expect_refactorizations`, the full contact system) and has at least
   !! METIS_MIN_NEQ equations.  METIS's analysis costs several times AMD's
   !! (1.5 s against 0.3 s at 3e5 equations) and saves 16-35 % of each
   !! factorization from 3e4 equations on: it pays back after 3 to 9
   !! factorizations, never in one (the Schur path, a model without contact).
   !! Measurements: docs/performance.md, "Orderings".
   integer, parameter :: ORDERING_DEFAULT = -1
   !> Smallest model ordered by METIS by default (below it the factorizations
   !! measured no faster with METIS).
   integer, parameter :: METIS_MIN_NEQ = 20000

contains

   !> The ordering an analysis is to use: `ordering`, or for ORDERING_DEFAULT METIS when
   !! many factorizations of a pattern of at least `min_neq` equations are expected,
   !! else AMD.  (METIS without METIS in the build: the caller falls back to AMD.)
   pure integer function choose_ordering(ordering, many, neq, min_neq) result(k)
      integer, intent(in) :: ordering        !! the ordering asked for, or ORDERING_DEFAULT
      logical, intent(in) :: many            !! many factorizations of the pattern expected
      integer, intent(in) :: neq             !! equations of the pattern
      integer, intent(in) :: min_neq         !! smallest pattern METIS orders by default
      k = ordering
      if (k /= ORDERING_DEFAULT) return
      k = ORDERING_AMD
      if (many .and. neq >= min_neq) k = ORDERING_METIS
   end function choose_ordering

   !> An ordering in words, for the listing; `missing`: METIS was asked for and the build
   !! has none (AMD was used instead).
   pure function ordering_text(k, missing) result(s)
      integer, intent(in) :: k           !! ordering code (INFOG(7), or ORDERING_METIS)
      logical, intent(in) :: missing
      character(len=:), allocatable :: s
      select case (k)
      case (ORDERING_AMD)
         s = 'AMD ordering'
      case (ORDERING_METIS)
         s = 'METIS nested-dissection ordering'
      case (ORDERING_SCOTCH)
         s = 'SCOTCH ordering'
      case (ORDERING_PORD)
         s = 'PORD ordering'
      case default
         s = 'MUMPS ordering '//itoa(k)
      end select
      if (missing) s = s//' (METIS would be used: this build has no METIS)'
   end function ordering_text

   !> PERM_IN (the place of every equation in the pivot order) from METIS's nested
   !! dissection: of the whole pattern, or, with Schur variables, of the pattern of the other
   !! equations, the Schur variables placed last in the order of `schur_vars` (they are not
   !! eliminated).
   subroutine metis_perm_in(cp, rows, schur_vars, perm_in, status)
      integer, intent(in) :: cp(0:)             !! (0:neq) column pointers of the upper pattern
      integer, intent(in) :: rows(:)            !! rows of each column
      integer, intent(in) :: schur_vars(:)      !! Schur variables (LISTVAR_SCHUR), may be none
      integer, intent(out) :: perm_in(:)        !! (neq)
      type(status_t), intent(inout) :: status
      integer, allocatable :: sub(:), xadj(:), adjncy(:), place(:)
      integer :: n, nsub, i, k
      n = ubound(cp, 1)
      call reduced_graph(cp, rows, schur_vars, sub, xadj, adjncy)
      nsub = size(xadj) - 1
      allocate (place(nsub + 1))
      call nested_dissection(nsub, xadj, adjncy, place, status)
      if (.not. status%ok()) then
         status%message = 'mumps solver: METIS ordering: '//status%message
         return
      end if
      do i = 1, n
         if (sub(i) > 0) perm_in(i) = place(sub(i))
      end do
      do k = 1, size(schur_vars)
         perm_in(schur_vars(k)) = nsub + k
      end do
   end subroutine metis_perm_in
end module mumps_ordering
