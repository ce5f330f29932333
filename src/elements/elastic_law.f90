!> Isotropic linear elasticity for plane stress, plane strain and axisymmetry.
!!
!! The elasticity matrix acts on the 4-component strain vector
!! (eps_xx, eps_yy, gamma_xy, eps_zz) and gives (sig_xx, sig_yy, tau_xy, sig_zz),
!! with zz the hoop direction theta in axisymmetry.  For plane problems the
!! 4th row and column are zero: sig_zz is 0 in plane stress and
!! nu (sig_xx + sig_yy) in plane strain, supplied by the stress recovery.
!!
!! Ref: Hinton & Owen, *Finite Element Programming* (1977), routine MODPS;
!!      Zienkiewicz & Taylor, *The Finite Element Method*, vol. 1
!!      (plane and axisymmetric elasticity).
module elastic_law
   use kinds, only: dp
   implicit none
   private

   public :: d_matrix, elastic_constants_valid

contains

   !> True if E > 0 and -1 < nu < 1/2, the range in which `d_matrix` is
   !! positive definite for every analysis type.
   pure logical function elastic_constants_valid(young, poiss)
      real(dp), intent(in) :: young   !! Young's modulus [stress]
      real(dp), intent(in) :: poiss   !! Poisson's ratio [-]

      elastic_constants_valid = young > 0.0_dp .and. poiss > -1.0_dp .and. poiss < 0.5_dp
   end function elastic_constants_valid

   !> Elasticity matrix D (MODPS), 4x4 on (xx, yy, xy, zz).
   !!
   !! Plane stress:  D11 = D22 = E/(1-nu²), D12 = nu E/(1-nu²), D33 = G.
   !! Plane strain and axisymmetry: c = E(1-nu)/((1+nu)(1-2nu)),
   !! D11 = D22 (= D44 axisymmetric) = c, off-diagonal normal terms
   !! c nu/(1-nu), D33 = G = E/(2(1+nu)).
   !! Outside the valid range (see `elastic_constants_valid`) D is returned
   !! as zero instead of dividing by zero; the reader rejects such input.
   !!
   !! Ref: Hinton & Owen (1977), MODPS; Zienkiewicz & Taylor, vol. 1
   !!      (D matrices of plane stress, plane strain and axisymmetry).
   pure subroutine d_matrix(ntype, young, poiss, dmatx)
      integer, intent(in) :: ntype           !! 1 plane stress, 2 plane strain, 3 axisymmetric
      real(dp), intent(in) :: young          !! Young's modulus [stress]
      real(dp), intent(in) :: poiss          !! Poisson's ratio [-]
      real(dp), intent(out) :: dmatx(4, 4)   !! elasticity matrix [stress]
      real(dp) :: const, conss

      dmatx = 0.0_dp
      if (.not. elastic_constants_valid(young, poiss)) return
      select case (ntype)
      case (1)
         const = young/(1.0_dp - poiss*poiss)
         dmatx(1, 1) = const
         dmatx(2, 2) = const
         dmatx(1, 2) = const*poiss
         dmatx(2, 1) = const*poiss
         dmatx(3, 3) = 0.5_dp*const*(1.0_dp - poiss)
      case (2, 3)
         const = young*(1.0_dp - poiss)/((1.0_dp + poiss)*(1.0_dp - 2.0_dp*poiss))
         conss = const*poiss/(1.0_dp - poiss)
         dmatx(1, 1) = const
         dmatx(2, 2) = const
         dmatx(1, 2) = conss
         dmatx(2, 1) = conss
         dmatx(3, 3) = 0.5_dp*young/(1.0_dp + poiss)
         if (ntype == 3) then
            dmatx(4, 4) = const
            dmatx(1, 4) = conss
            dmatx(4, 1) = conss
            dmatx(2, 4) = conss
            dmatx(4, 2) = conss
         end if
      end select
   end subroutine d_matrix

end module elastic_law
