!> What a computed residual can resolve: the one definition of the
!! round-off floor that Newton's convergence test, the bodies' equilibrium
!! audit and the invariant checks of the contact forces share.
!!
!! A residual r = sum_k c_k (loads, element and spring force contributions,
!! a force and the increments summed into it) is computed in floating point
!! with an error of at most gamma_n sum_k |c_k|, gamma_n = n u / (1 - n u),
!! u = epsilon/2 the unit round-off, n the number of terms (N. J. Higham,
!! Accuracy and Stability of Numerical Algorithms, 2nd ed., SIAM 2002, §3.1
!! and §3.5: |fl(A x) - A x| <= gamma_n |A| |x|; the solution of A x = b
!! satisfies (A + dA) x = b with |dA| of the same order, §9.1).  What cancels
!! is the *magnitude* M = sum_k |c_k|, not the net value: a nearly rigid body
!! moving by much more than it deforms has internal forces K u that are the
!! small difference of terms 1e7 times larger, and a pair force at zero load
!! is the difference of the increments that loaded and unloaded it.  So a
!! residual is resolved only down to ROUNDOFF_UNITS * epsilon * M, and a
!! criterion "|r| <= tol * scale" becomes
!!
!!     |r| <= tol * scale + ROUNDOFF_UNITS * epsilon * M.
!!
!! For ordinary stiffness M is a few to 1e4 times the scale, the floor
!! 1e-15 to 1e-12 of it, far below the tolerances (1e-10, 1e-8): the criterion
!! is tol.  The floor engages only where M / scale exceeds ~1e5 -- and at zero
!! load, where the scale itself vanishes and the floor alone keeps the
!! criterion meaningful.
module roundoff
   use kinds, only: dp
   implicit none
   private
   public :: ROUNDOFF_UNITS, roundoff_floor, resolvable_limit

   !> The floor in units of epsilon times the magnitude that cancels.
   !! Higham's gamma_n for n = 32 terms (a node of a Q8 mesh couples to up
   !! to 21 nodes, 42 terms of K u, plus its springs and loads) is 16 epsilon;
   !! errors of independent terms add with random signs, so this is a bound
   !! the measured residuals stay below (docs/accuracy-and-stability.md).
   real(dp), parameter :: ROUNDOFF_UNITS = 16.0_dp

contains

   !> The absolute round-off of a residual whose terms cancel from the
   !! magnitude `magnitude` (the sum of the terms' absolute values).
   pure elemental real(dp) function roundoff_floor(magnitude) result(f)
      real(dp), intent(in) :: magnitude
      f = ROUNDOFF_UNITS*epsilon(1.0_dp)*abs(magnitude)
   end function roundoff_floor

   !> The limit of a relative residual |r| / scale: tol, raised by the
   !! round-off of terms of magnitude `magnitude` relative to `scale` (a
   !! scale of zero -- nothing loaded -- is taken as tiny: the limit is then
   !! the floor's, huge unless the magnitude is zero too).
   pure real(dp) function resolvable_limit(tol, scale, magnitude) result(limit)
      real(dp), intent(in) :: tol         !! the criterion (relative)
      real(dp), intent(in) :: scale       !! the force the residual is relative to
      real(dp), intent(in) :: magnitude   !! sum of |terms| that cancel in
                                          !! the residual (the same unit)
      limit = tol + roundoff_floor(magnitude)/max(scale, tiny(1.0_dp))
   end function resolvable_limit
end module roundoff
