!> Condensation of the bodies onto the contact equations (the fast path of
!! DESIGN.md: "condense the bodies onto the contact DOFs once (Schur
!! complement) so that an increment costs a small dense LAPACK solve").
!!
!! The bodies' stiffness K_AB is constant; only the springs K_c change, and
!! they act on the n_c contact equations c alone.  With K_AB factorized once,
!! the flexibility of the contact equations
!!
!!     G = E_c^T K_AB^-1 E_c        (n_c x n_c, n_c solves with unit vectors)
!!
!! turns every solve of [K_AB + K_c] dv = b into
!!
!!     w = K_AB^-1 b,  (I + G K_cc) dv_c = w_c,  dv = w - K_AB^-1 E_c K_cc dv_c,
!!
!! a dense system of order n_c (LAPACK dgesv) plus solves with the existing
!! factorization.  When b is itself supported on c, w_c = G b_c needs no
!! solve at all; the driver then defers the full-length correction to one solve
!! at the end of the increment.  Ref: the static condensation of substructures
!! (e.g. Bathe, Finite Element Procedures, sec. 8.2.4).
module condensation
   use kinds, only: dp, i8
   use errors, only: status_t, STAT_SOLVER, STAT_SINGULAR
   use strings, only: itoa
   use linear_solver, only: linear_solver_t
   implicit none
   private
   public :: condensed_t

   type :: condensed_t
      integer :: nc = 0                      !! contact equations
      integer, allocatable :: ceq(:)         !! their global equation numbers
      integer, allocatable :: pos(:)         !! (neq) position of an equation in ceq, 0 if none
      real(dp), allocatable :: g(:, :)       !! flexibility G (n_c x n_c)
      real(dp), allocatable :: kcc(:, :)     !! assembled spring matrix on c
      logical :: ready = .false.
   contains
      procedure :: setup => condensed_setup
      procedure :: zero_springs => condensed_zero_springs
      procedure :: add_spring => condensed_add_spring
      procedure :: solve_c => condensed_solve_c
      procedure :: memory_bytes => condensed_memory
   end type condensed_t

contains

   !> Flexibility of the contact equations from the factorized K_AB in `solver`.
   subroutine condensed_setup(this, solver, neq, ceq, status)
      class(condensed_t), intent(inout) :: this
      class(linear_solver_t), intent(inout) :: solver   !! holds factorized K_AB
      integer, intent(in) :: neq
      integer, intent(in) :: ceq(:)                      !! distinct equation numbers (> 0)
      type(status_t), intent(inout) :: status
      real(dp), allocatable :: e(:)
      integer :: j, k
      this%nc = size(ceq)
      this%ceq = ceq
      allocate (this%pos(neq))
      this%pos = 0
      do k = 1, this%nc
         this%pos(ceq(k)) = k
      end do
      if (allocated(this%g)) deallocate (this%g)
      if (allocated(this%kcc)) deallocate (this%kcc)
      allocate (this%g(this%nc, this%nc), this%kcc(this%nc, this%nc), e(neq))
      do j = 1, this%nc
         e = 0.0_dp
         e(ceq(j)) = 1.0_dp
         call solver%solve(e, status)
         if (.not. status%ok()) return
         this%g(:, j) = e(ceq)
      end do
      ! symmetric in exact arithmetic: remove the round-off asymmetry
      this%g = 0.5_dp*(this%g + transpose(this%g))
      this%ready = .true.
   end subroutine condensed_setup

   subroutine condensed_zero_springs(this)
      class(condensed_t), intent(inout) :: this
      this%kcc = 0.0_dp
   end subroutine condensed_zero_springs

   !> Add a spring matrix with global equations ieq (<= 0 skipped; every
   !! positive one must be a contact equation).
   subroutine condensed_add_spring(this, ieq, ke)
      class(condensed_t), intent(inout) :: this
      integer, intent(in) :: ieq(:)
      real(dp), intent(in) :: ke(:, :)
      integer :: a, b, pa, pb
      do b = 1, size(ieq)
         if (ieq(b) <= 0) cycle
         pb = this%pos(ieq(b))
         do a = 1, size(ieq)
            if (ieq(a) <= 0) cycle
            pa = this%pos(ieq(a))
            this%kcc(pa, pb) = this%kcc(pa, pb) + ke(a, b)
         end do
      end do
   end subroutine condensed_add_spring

   !> Solve (I + G K_cc) x = wc for the contact part of a solution (LAPACK
   !! dgetrf/dgetrs).  A pivot below 1e-12 of its column's largest original
   !! entry means a singular system (e.g. a body whose springs all opened),
   !! reported like the skyline solver's zero pivots.
   subroutine condensed_solve_c(this, wc, x, status)
      class(condensed_t), intent(in) :: this
      real(dp), intent(in) :: wc(:)
      real(dp), intent(out) :: x(:)
      type(status_t), intent(inout) :: status
      real(dp), allocatable :: a(:, :), b(:, :), colmax(:)
      integer, allocatable :: ipiv(:)
      integer :: info, k
      interface
         subroutine dgetrf(m, n, a, lda, ipiv, info)
            import :: dp
            integer, intent(in) :: m, n, lda
            real(dp), intent(inout) :: a(lda, *)
            integer, intent(out) :: ipiv(*), info
         end subroutine dgetrf
         subroutine dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
            import :: dp
            character(len=1), intent(in) :: trans
            integer, intent(in) :: n, nrhs, lda, ldb
            real(dp), intent(in) :: a(lda, *)
            integer, intent(in) :: ipiv(*)
            real(dp), intent(inout) :: b(ldb, *)
            integer, intent(out) :: info
         end subroutine dgetrs
      end interface
      x = 0.0_dp
      if (this%nc == 0) return
      a = matmul(this%g, this%kcc)
      do k = 1, this%nc
         a(k, k) = a(k, k) + 1.0_dp
      end do
      colmax = maxval(abs(a), dim=1)
      allocate (b(this%nc, 1), ipiv(this%nc))
      call dgetrf(this%nc, this%nc, a, this%nc, ipiv, info)
      if (info < 0) then
         call status%set(STAT_SOLVER, 'LAPACK dgetrf: illegal argument '//itoa(-info))
         return
      end if
      do k = 1, this%nc
         if (abs(a(k, k)) <= 1.0e-12_dp*colmax(k)) then
            call status%set(STAT_SINGULAR, 'zero pivot at contact equation '//itoa(this%ceq(k))// &
                            ' of the condensed contact system')
            return
         end if
      end do
      b(:, 1) = wc
      call dgetrs('N', this%nc, 1, a, this%nc, ipiv, b, this%nc, info)
      if (info /= 0) then
         call status%set(STAT_SOLVER, 'LAPACK dgetrs: illegal argument '//itoa(-info))
         return
      end if
      x = b(:, 1)
   end subroutine condensed_solve_c

   pure integer(i8) function condensed_memory(this) result(bytes)
      class(condensed_t), intent(in) :: this
      bytes = 3_i8*int(this%nc, i8)**2*8_i8
   end function condensed_memory
end module condensation
