!> The first iterate of an increment's Newton iteration, predicted from the
!! last accepted increment (issue 28: fewer solutions per increment).
!!
!! Without a prediction the first solution of an increment starts from the
!! committed state with the springs' tangents there, and the Newton return of
!! the rough law then needs 4 (stick) to 7 (slip) solutions to converge.  Under
!! a load that grows in proportion, the displacement increment of the pairs
!! changes little from one increment to the next, so the first iterate is taken
!! as the last accepted increment at the pairs' dofs scaled by the ratio of the
!! load-factor increments (linear extrapolation),
!!
!!     du_0 = s du_prev,   s = (dlam . dlam_prev) / |dlam_prev|^2,
!!
!! the prescribed increments kept at the restrained dofs.  Where the two
!! accepted increments before lie along the same direction, with step ratios
!! within [1/2, 2] and the first increment of the run not among them, the
!! parabola through the last three committed states is used instead
!! (`quadratic_weights`; equal steps: du_0 = 2 du_prev - du_prev2), unless its
!! correction of the straight line exceeds a quarter of the straight line's
!! prediction (`gentle_curvature`).  On the slip increments of the many-pairs
!! punch the straight line leaves the first iterate about 1e-3 of the increment
!! off the converged one and the Newton return converges only linearly there
!! (the slipping pairs' tangent misses dF_T/du_n = mu K_n, which the symmetric
!! systems cannot hold), so the error the prediction leaves sets the count: the
!! parabola saves a solution in most increments (docs/performance.md, sitting 11).  The springs are
!! evaluated at du_0 (modes, forces F(du_0), tangents K_t), and the first
!! solution is the Newton step from there, written as one solve from the
!! committed state, because the bodies are linear:
!!
!!     [K_AB + K_t] du_1 = b + F_c + K_t du_0 - F(du_0)
!!
!! (b the usual first right-hand side, F_c the committed spring forces): only
!! the contact equations' right-hand side changes, so a condensed system
!! recovers the full field of the attempt as before (the part of its first
!! right-hand side away from the contact equations is the load's).  The
!! solution is then shifted by -du_0 (`shift_first`) so that the iteration
!! continues with the correction du_1 - du_0, its predicted spring forces
!! F(du_0) + K_t (du_1 - du_0) and its correction norm as without a
!! prediction.  The converged increment solves the same equations to the same
!! tolerances (CONTACT CONVERGE TOLR, TOLU): it differs from the one reached
!! from the committed state by what those tolerances leave (measured in
!! docs/performance.md).
!!
!! Used only where it is safe and pays: the Newton return of rough pairs
!! without ideal pairs or pretension sections, in models of PREDICT_MIN_PAIRS
!! contact pairs and more (the driver's default), not in the first increment
!! (nothing to extrapolate), not for a load-factor increment that is not a
!! positive multiple of the last one (a reversal, a hold, another load case),
!! and not in the second pass of an attempt whose system turned singular.  An
!! attempt that starts from a prediction is not accepted on its first
!! solution's force alone (the exemption of a first solution from the
!! committed state, which is the linear solution of the increment): its first
!! correction is held to TOLU like every later one.
module increment_predictor
   use kinds, only: dp
   use contact_assembly, only: contact_springs_t
   use contact_types, only: contact_def_t
   use contact_algorithm, only: contact_state_t, evaluate_pairs
   implicit none
   private
   public :: increment_predictor_t, PREDICT_MIN_PAIRS, quadratic_weights

   !> The smallest model (in contact pairs) the driver predicts for by default.  A solution of
   !! a few pairs costs little, and the prediction changes the path of the iteration (which
   !! modes a pair passes through on the way, how often a pair changes its mode within an
   !! increment: the guard against chatter counts them), so small models keep the iteration
   !! from the committed state; from a few hundred pairs on the solutions are what a run costs
   !! (docs/performance.md, "Fewer solutions per increment").
   integer, parameter :: PREDICT_MIN_PAIRS = 200

   !> The parabola through the last three committed states is used for steps whose ratios
   !! (the new step to the last, the last to the one before) lie in [STEP_RATIO_MIN,
   !! STEP_RATIO_MAX], never through the first increment of the run (the pairs closing
   !! from zero force: the most curved stretch of the path), and only where its correction
   !! of the straight line is at most CURVATURE_MAX of the straight line's prediction
   !! (gentle_curvature); else the straight line.
   real(dp), parameter :: STEP_RATIO_MIN = 0.5_dp, STEP_RATIO_MAX = 2.0_dp
   real(dp), parameter :: CURVATURE_MAX = 0.25_dp

   !> The last accepted increment and the prediction of the attempt under way.
   type :: increment_predictor_t
      logical :: enabled = .false.                !! predictions allowed (set by the driver)
      logical :: active = .false.                 !! the first solution is still to be shifted
      logical :: predicted = .false.              !! the attempt under way started from du0
      integer :: predictions = 0                  !! attempts that started from a prediction
      integer :: accepted = 0                     !! increments accepted since the last forget
      real(dp), allocatable :: du_last(:, :)      !! (2, npoin) last accepted increment
      real(dp), allocatable :: dlam_last(:)       !! its load-factor increments
      real(dp), allocatable :: du_prev(:, :)      !! (2, npoin) the accepted increment before it
      real(dp), allocatable :: dlam_prev(:)       !! its load-factor increments
      real(dp), allocatable :: du0(:, :)          !! (2, npoin) the prediction, zero off the pairs
   contains
      procedure :: accept => predictor_accept
      procedure :: forget => predictor_forget
      procedure :: predict => predictor_predict
      procedure :: shift_first => predictor_shift_first
   end type increment_predictor_t

contains

   !> An accepted increment du of the load-factor increments dlam: the base of
   !! the next prediction.
   subroutine predictor_accept(this, du, dlam)
      class(increment_predictor_t), intent(inout) :: this
      real(dp), intent(in) :: du(:, :)
      real(dp), intent(in) :: dlam(:)
      if (.not. this%enabled) return
      this%accepted = this%accepted + 1
      if (allocated(this%du_last)) then
         call move_alloc(this%du_last, this%du_prev)
         call move_alloc(this%dlam_last, this%dlam_prev)
      end if
      this%du_last = du
      this%dlam_last = dlam
   end subroutine predictor_accept

   !> No prediction for the next attempt (nothing accepted yet, or a new start).
   subroutine predictor_forget(this)
      class(increment_predictor_t), intent(inout) :: this
      if (allocated(this%du_last)) deallocate (this%du_last)
      if (allocated(this%dlam_last)) deallocate (this%dlam_last)
      if (allocated(this%du_prev)) deallocate (this%du_prev)
      if (allocated(this%dlam_prev)) deallocate (this%dlam_prev)
      this%accepted = 0
      this%active = .false.
      this%predicted = .false.
   end subroutine predictor_forget

   !> Start an attempt from the prediction, if there is one (see the module
   !! header): du gets du0 at the pairs' free dofs, the springs are evaluated
   !! there (st), rvec gets their forces F(du0) and rhs the terms F_c + K_t du0
   !! - F(du0) at the contact equations.  Called after start_forces (rvec holds
   !! the committed forces F_c) and before the first solution; leaves
   !! everything as it is when no prediction is made (`this%active` false).
   subroutine predictor_predict(this, springs, cdef, st, dlam, first, restrained, du, rvec, rhs)
      class(increment_predictor_t), intent(inout) :: this
      type(contact_springs_t), intent(inout) :: springs
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(inout) :: st
      real(dp), intent(in) :: dlam(:)             !! load-factor increments of the attempt
      logical, intent(in) :: first                !! first increment of the run
      logical, intent(in) :: restrained(:, :)     !! (2, npoin)
      real(dp), intent(inout) :: du(:, :)         !! (2, npoin) prescribed increments in, du0 out
      real(dp), intent(inout) :: rvec(:, :)       !! (nd, npair) F_c in, F(du0) out
      real(dp), intent(inout) :: rhs(:)           !! (neq) the first right-hand side
      real(dp), allocatable :: rlin(:, :), radd(:)
      logical, allocatable :: changed(:)
      real(dp) :: s, s2, c1, c2
      integer :: j, k, ip
      logical :: quad
      this%active = .false.
      this%predicted = .false.
      if (.not. this%enabled .or. first .or. .not. allocated(this%du_last)) return
      if (size(this%dlam_last) /= size(dlam) .or. size(this%du_last, 2) /= size(du, 2)) return
      s = load_ratio(this%dlam_last, dlam)
      if (s <= 0.0_dp) return
      ! du0 = c1 du_last + c2 du_prev (quadratic_weights)
      s2 = 0.0_dp
      if (allocated(this%du_prev) .and. this%accepted >= 3) then
         if (size(this%dlam_prev) == size(dlam) .and. size(this%du_prev, 2) == size(du, 2)) then
            s2 = load_ratio(this%dlam_prev, this%dlam_last)
         end if
      end if
      call quadratic_weights(s, s2, c1, c2)
      quad = s2 >= STEP_RATIO_MIN .and. s2 <= STEP_RATIO_MAX .and. s <= STEP_RATIO_MAX
      if (quad) quad = gentle_curvature(cdef, restrained, s, c1, c2, this%du_last, this%du_prev)
      if (.not. quad) then
         c1 = s
         c2 = 0.0_dp
      end if
      if (.not. allocated(this%du0)) allocate (this%du0(2, size(du, 2)))
      this%du0 = 0.0_dp
      do j = 1, size(cdef%pairs)
         do k = 1, cdef%pairs(j)%nn
            ip = cdef%pairs(j)%nodes(k)
            ! (restrained dofs of the pairs hold the prescribed increments in both)
            if (quad) then
               this%du0(:, ip) = merge(du(:, ip), c1*this%du_last(:, ip) + c2*this%du_prev(:, ip), &
                                       restrained(:, ip))
            else
               this%du0(:, ip) = merge(du(:, ip), c1*this%du_last(:, ip), restrained(:, ip))
            end if
            du(:, ip) = this%du0(:, ip)
         end do
      end do
      allocate (changed(size(cdef%pairs)), rlin(size(rvec, 1), size(rvec, 2)), radd(size(rhs)))
      call evaluate_pairs(cdef, st, this%du0, changed, first)
      call springs%set_matrices(cdef, st)
      ! F_c + K_t du0 against F(du0): the Newton step's right-hand side at the contact equations
      call springs%predicted_forces(cdef%pairs, rvec, this%du0, rlin)
      call springs%residual_forces(cdef, st, rlin, rvec, radd)
      rhs = rhs + radd
      this%active = .true.
      this%predicted = .true.
      this%predictions = this%predictions + 1
   end subroutine predictor_predict

   !> After the first solution of an attempt that started from a prediction:
   !! the solution du_1 becomes the correction du_1 - du0 (zero at the
   !! restrained dofs of the pairs), as the iteration expects.
   subroutine predictor_shift_first(this, ddu)
      class(increment_predictor_t), intent(inout) :: this
      real(dp), intent(inout) :: ddu(:, :)
      if (.not. this%active) return
      ddu = ddu - this%du0
      this%active = .false.
   end subroutine predictor_shift_first

   !> The weights of du0 = c1 du_last + c2 du_prev: the parabola through the
   !! last three committed states u(t) along the direction of loading (t in
   !! units of the last increment: steps 1/s2 and 1 before, s after), at the
   !! new load,
   !!     d1 = du_last, d0 = s2 du_prev (difference quotients),
   !!     du0 = s d1 + s (s + 1) (d1 - d0) / (1 + 1/s2);
   !! with no increment before the last along the same direction (s2 = 0) the
   !! straight line, du0 = s du_last.  Equal steps: du0 = 2 du_last - du_prev.
   pure subroutine quadratic_weights(s, s2, c1, c2)
      real(dp), intent(in) :: s, s2
      real(dp), intent(out) :: c1, c2
      real(dp) :: q
      c1 = s
      c2 = 0.0_dp
      if (.not. (s2 >= STEP_RATIO_MIN .and. s2 <= STEP_RATIO_MAX .and. s <= STEP_RATIO_MAX)) return
      q = s*(s + 1.0_dp)/(1.0_dp + 1.0_dp/s2)
      c1 = s + q
      c2 = -q*s2
   end subroutine quadratic_weights

   !> Whether the parabola's correction of the straight line, (c1 - s) du_last
   !! + c2 du_prev, is at most CURVATURE_MAX of the straight line's prediction s
   !! du_last (largest values over the pairs' free dofs): a load path whose
   !! response bends more than that (a pair closing from zero force, a stick
   !! zone giving way) is extrapolated along the straight line.
   pure logical function gentle_curvature(cdef, restrained, s, c1, c2, du_last, du_prev) result(ok)
      type(contact_def_t), intent(in) :: cdef
      logical, intent(in) :: restrained(:, :)
      real(dp), intent(in) :: s, c1, c2, du_last(:, :), du_prev(:, :)
      real(dp) :: lin, bend
      integer :: j, k, ip, i
      lin = 0.0_dp
      bend = 0.0_dp
      do j = 1, size(cdef%pairs)
         do k = 1, cdef%pairs(j)%nn
            ip = cdef%pairs(j)%nodes(k)
            do i = 1, 2
               if (restrained(i, ip)) cycle
               lin = max(lin, abs(s*du_last(i, ip)))
               bend = max(bend, abs((c1 - s)*du_last(i, ip) + c2*du_prev(i, ip)))
            end do
         end do
      end do
      ok = bend <= CURVATURE_MAX*lin
   end function gentle_curvature

   !> s with dlam = s dlam_last (to 1e-9 of |dlam|), else 0: a prediction
   !! extrapolates only along the last increment's direction of loading.
   pure real(dp) function load_ratio(dlam_last, dlam) result(s)
      real(dp), intent(in) :: dlam_last(:), dlam(:)
      real(dp) :: d2
      s = 0.0_dp
      d2 = dot_product(dlam_last, dlam_last)
      if (.not. d2 > 0.0_dp) return
      s = dot_product(dlam_last, dlam)/d2
      if (maxval(abs(dlam - s*dlam_last)) > 1.0e-9_dp*maxval(abs(dlam))) s = 0.0_dp
   end function load_ratio
end module increment_predictor
