!> The full system with a kept factorization (issue 28): K_AB + K_c factorized
!! for one set of springs, and the systems of the following sets solved by
!! conjugate gradients preconditioned by those factors, until an iteration
!! needs too many steps; then the current springs are factorized.
!!
!! Newton's new tangents change the springs only, on the contact equations:
!! A = A_f + D with A_f = K_AB + K_c,f (factorized) and D = K_c - K_c,f, a sum
!! of the pairs' small matrices.  The iteration needs no product with K_AB:
!! A_f p is carried along (A_f z = r is the back-substitution itself), so each
!! step costs one back-substitution and a product with D.  It stops when the
!! preconditioned residual (the correction a direct solve would still make) is
!! KEPT_TOLERANCE of the solution, the round-off of a direct solve of these
!! systems; the Newton iteration around it is unchanged.  Measured on the
!! benchmark of many pairs (docs/performance.md, "A kept factorization and the
!! heap"): a back-substitution costs about a fifth of a factorization there.
!!
!! A factorization is made (as by full_system) when
!! * the model has fewer than KEPT_MIN_PAIRS pairs or KEPT_MIN_EQUATIONS equations
!!   (its factorizations are cheap, a back-substitution a large share of one),
!! * a pair lost a spring since the factorization (its K_n or K_T became zero:
!!   the new system may be singular, which only a factorization detects and
!!   names; the driver gives the springs present in `support`),
!! * the iteration did not converge in KEPT_MAX_ITERATIONS steps (the solve is
!!   then repeated with the new factors), or the last one took more than half
!!   of them.
module kept_factor_system
   use kinds, only: dp, i8
   use errors, only: status_t
   use full_system, only: full_system_t
   implicit none
   private
   public :: kept_factor_system_t, KEPT_MIN_PAIRS, KEPT_MIN_EQUATIONS, KEPT_MAX_ITERATIONS, &
             KEPT_TOLERANCE

   !> Pairs from which a factorization is kept (as the increment predictor's limit).
   integer, parameter :: KEPT_MIN_PAIRS = 200
   !> Equations from which a factorization is kept: below, a back-substitution costs too large a
   !! share of a factorization (measured: 401 pairs on 6 436 DOFs 25 % slower with the kept
   !! factor, 3 001 pairs on 19 226 DOFs 4 % faster; docs/performance.md).
   integer, parameter :: KEPT_MIN_EQUATIONS = 15000
   !> Steps of the iteration before the springs are factorized.
   integer, parameter :: KEPT_MAX_ITERATIONS = 6
   !> Preconditioned residual (max norm) over the solution (max norm) at which it stops.
   real(dp), parameter :: KEPT_TOLERANCE = 1.0e-13_dp

   type, extends(full_system_t) :: kept_factor_system_t
      integer :: min_pairs = KEPT_MIN_PAIRS  !! pairs from which factors are kept
      integer :: min_equations = KEPT_MIN_EQUATIONS  !! and equations
      logical :: active = .false.         !! enough pairs: factors are kept
      logical :: factored = .false.       !! the factors are of the springs kf
      logical :: pending = .false.        !! the springs kc differ from kf
      logical :: refactor_next = .false.  !! the last iteration was long
      real(dp), allocatable :: kf(:, :, :)   !! (nd, nd, npair) springs of the factors
      real(dp), allocatable :: kc(:, :, :)   !! (nd, nd, npair) current springs
      integer, allocatable :: support_f(:)   !! support of the factors' springs
      integer, allocatable :: drow(:), dcol(:)  !! D = K_c - K_c,f by entries (free
      real(dp), allocatable :: dval(:)          !! equations only), ndelta of them
      integer :: ndelta = 0
      integer :: factorizations = 0          !! factorizations made
      integer :: iterated = 0                !! solves by the iteration
      integer :: steps = 0                   !! their steps in all
   contains
      procedure :: prepare => kept_prepare
      procedure :: set_springs => kept_set_springs
      procedure :: solve => kept_solve
      procedure :: memory_bytes => kept_memory
   end type kept_factor_system_t

contains

   subroutine kept_prepare(this, kref, status)
      class(kept_factor_system_t), intent(inout) :: this
      real(dp), intent(in) :: kref(:, :, :)
      type(status_t), intent(inout) :: status
      call this%full_system_t%prepare(kref, status)
      this%active = .false.
      if (allocated(this%peq)) this%active = size(this%peq, 2) >= this%min_pairs .and. &
                                             this%neq >= this%min_equations
      this%factored = .false.
      this%pending = .false.
   end subroutine kept_prepare

   !> The springs of the current modes: kept for the iteration while the
   !! factors may precondition it, else factorized.
   subroutine kept_set_springs(this, kc, status)
      class(kept_factor_system_t), intent(inout) :: this
      real(dp), intent(in) :: kc(:, :, :)
      type(status_t), intent(inout) :: status
      if (.not. this%active) then
         call this%full_system_t%set_springs(kc, status)
         return
      end if
      if (this%factored .and. .not. this%refactor_next .and. support_kept(this)) then
         this%kc = kc
         call collect_delta(this)
         this%pending = this%ndelta > 0
         return
      end if
      call factor_springs(this, kc, status)
   end subroutine kept_set_springs

   !> No pair lost a spring since the factorization (the new system is regular).
   pure logical function support_kept(this) result(kept)
      class(kept_factor_system_t), intent(in) :: this
      kept = .false.
      if (.not. (allocated(this%support) .and. allocated(this%support_f))) return
      if (size(this%support) /= size(this%support_f)) return
      kept = all(iand(this%support_f, not(this%support)) == 0)
   end function support_kept

   subroutine factor_springs(this, kc, status)
      class(kept_factor_system_t), intent(inout) :: this
      real(dp), intent(in) :: kc(:, :, :)
      type(status_t), intent(inout) :: status
      this%pending = .false.
      this%refactor_next = .false.
      this%factored = .false.
      call this%full_system_t%set_springs(kc, status)
      if (.not. status%ok()) return
      this%factorizations = this%factorizations + 1
      this%factored = .true.
      this%kf = kc
      if (allocated(this%support)) then
         this%support_f = this%support
      else if (allocated(this%support_f)) then
         deallocate (this%support_f)
      end if
   end subroutine factor_springs

   !> One solve with the current springs: by the iteration where they differ
   !! from the factors', else (or when it does not converge) directly.
   subroutine kept_solve(this, b, du, status)
      class(kept_factor_system_t), intent(inout) :: this
      real(dp), intent(inout) :: b(:)
      real(dp), intent(inout) :: du(:, :)
      type(status_t), intent(inout) :: status
      real(dp), allocatable :: x(:)
      integer :: ip, idof, steps
      logical :: converged
      if (.not. this%pending) then
         call this%full_system_t%solve(b, du, status)
         return
      end if
      call iterate(this, b, x, steps, converged, status)
      if (.not. status%ok()) return
      if (.not. converged) then
         call factor_springs(this, this%kc, status)
         if (.not. status%ok()) return
         call this%full_system_t%solve(b, du, status)
         return
      end if
      this%iterated = this%iterated + 1
      this%steps = this%steps + steps
      this%refactor_next = steps > KEPT_MAX_ITERATIONS/2
      b = x
      do ip = 1, size(this%id, 2)
         do idof = 1, 2
            if (this%id(idof, ip) > 0) du(idof, ip) = b(this%id(idof, ip))
         end do
      end do
   end subroutine kept_solve

   !> Conjugate gradients on (A_f + D) x = b preconditioned by A_f's factors,
   !! from x = 0; A_f p carried along (ap), so no product with K_AB.
   subroutine iterate(this, b, x, steps, converged, status)
      class(kept_factor_system_t), intent(inout) :: this
      real(dp), intent(in) :: b(:)
      real(dp), allocatable, intent(out) :: x(:)
      integer, intent(out) :: steps
      logical, intent(out) :: converged
      type(status_t), intent(inout) :: status
      real(dp), allocatable :: r(:), z(:), p(:), ap(:), q(:)
      real(dp) :: rz, rz_new, pq, alpha, beta
      converged = .false.
      steps = 0
      allocate (x(size(b)))
      x = 0.0_dp
      r = b
      z = r
      call this%solver%solve(z, status)
      if (.not. status%ok()) return
      p = z
      ap = r
      rz = dot_product(r, z)
      if (.not. rz > 0.0_dp) then
         ! (a zero right-hand side: the solution is zero)
         converged = maxval(abs(b)) <= 0.0_dp
         return
      end if
      do steps = 1, KEPT_MAX_ITERATIONS
         q = ap
         call add_delta(this, p, q)
         pq = dot_product(p, q)
         if (.not. pq > 0.0_dp) return
         alpha = rz/pq
         x = x + alpha*p
         r = r - alpha*q
         z = r
         call this%solver%solve(z, status)
         if (.not. status%ok()) return
         if (maxval(abs(z)) <= KEPT_TOLERANCE*maxval(abs(x))) then
            converged = .true.
            return
         end if
         rz_new = dot_product(r, z)
         beta = rz_new/rz
         rz = rz_new
         p = z + beta*p
         ap = r + beta*ap
      end do
      steps = KEPT_MAX_ITERATIONS
   end subroutine iterate

   !> The entries of D = K_c - K_c,f at free equations (drow, dcol, dval).
   subroutine collect_delta(this)
      class(kept_factor_system_t), intent(inout) :: this
      integer :: j, a, c, n, nd
      real(dp) :: d
      nd = size(this%peq, 1)
      n = count(abs(this%kc - this%kf) > 0.0_dp)
      if (.not. allocated(this%dval)) allocate (this%drow(0), this%dcol(0), this%dval(0))
      if (size(this%dval) < n) then
         deallocate (this%drow, this%dcol, this%dval)
         allocate (this%drow(n), this%dcol(n), this%dval(n))
      end if
      n = 0
      do j = 1, size(this%peq, 2)
         do c = 1, nd
            if (this%peq(c, j) <= 0) cycle
            do a = 1, nd
               d = this%kc(a, c, j) - this%kf(a, c, j)
               if (this%peq(a, j) <= 0 .or. .not. abs(d) > 0.0_dp) cycle
               n = n + 1
               this%drow(n) = this%peq(a, j)
               this%dcol(n) = this%peq(c, j)
               this%dval(n) = d
            end do
         end do
      end do
      this%ndelta = n
   end subroutine collect_delta

   !> y += D v.
   pure subroutine add_delta(this, v, y)
      class(kept_factor_system_t), intent(in) :: this
      real(dp), intent(in) :: v(:)
      real(dp), intent(inout) :: y(:)
      integer :: k
      do k = 1, this%ndelta
         y(this%drow(k)) = y(this%drow(k)) + this%dval(k)*v(this%dcol(k))
      end do
   end subroutine add_delta

   pure function kept_memory(this) result(bytes)
      class(kept_factor_system_t), intent(in) :: this
      integer(i8) :: bytes
      bytes = 0
      if (allocated(this%kf)) bytes = bytes + 8_i8*size(this%kf, kind=i8)
      if (allocated(this%kc)) bytes = bytes + 8_i8*size(this%kc, kind=i8)
   end function kept_memory
end module kept_factor_system
