!> Kernels of the recovery-based (Zienkiewicz-Zhu) error estimate: the
!! least-squares fit of a polynomial to the sampled stresses of one patch
!! (superconvergent patch recovery), its value at a point, and the energy
!! norm integrals of one element.
!!
!! The patch fit: sigma*(x, y) = P(xh, yh) a, fitted to the stresses sampled
!! at the Gauss points of the patch's elements by least squares, one set of
!! coefficients per stress component, in the local coordinates
!! xh = (x - x_c)/h, yh = (y - y_c)/h of the patch (centre x_c, size h), which
!! keeps the normal equations well conditioned.  The polynomial P has the
!! terms of the element's own interpolation: {1, x, y} (T3), {1, x, y, xy}
!! (Q4), the serendipity {.., x^2, y^2, x^2 y, x y^2} (Q8), the biquadratic
!! {.., x^2 y^2} (Q9).  A patch with fewer points than terms, or whose points
!! do not determine the polynomial, is reported (`ok` false); the caller
!! takes a smaller basis there.
!!
!! Energy norm: ||s||_E^2 = int s^T D^-1 s dV over the element, with the
!! compliance of the analysis type (plane stress, plane strain -- its in-plane
!! compliance, sig_zz being dependent --, axisymmetric with the hoop stress),
!! integrated by the element's own Gauss rule with the weight thick dA or
!! 2 pi r dA.
!!
!! Ref: Zienkiewicz & Zhu, The superconvergent patch recovery and a
!!      posteriori error estimates, Part 1: The recovery technique, IJNME 33
!!      (1992) 1331-1364; Part 2: Error estimates and adaptivity, IJNME 33
!!      (1992) 1365-1382.
module error_estimator
   use kinds, only: dp, two_pi
   use quadrature, only: max_gp, element_gauss_rule
   use shape_2d, only: shape_functions
   use kinematics_2d, only: jacobian_2d
   implicit none
   private

   public :: MAX_TERMS, recovery_terms, fit_basis_xy, patch_fit, patch_value, stress_energy, &
             gauss_volumes, element_error_energy

   integer, parameter :: MAX_TERMS = 9   !! most terms of a recovery polynomial (Q9)

contains

   !> Terms of the recovery polynomial of an element with `nnode` nodes: 3
   !! (T3, linear), 4 (Q4, bilinear), 8 (Q8, serendipity), 9 (Q9, biquadratic);
   !! 0 for an unsupported element.
   pure integer function recovery_terms(nnode) result(nterm)
      integer, intent(in) :: nnode   !! nodes per element
      select case (nnode)
      case (3, 4, 8, 9)
         nterm = nnode
      case default
         nterm = 0
      end select
   end function recovery_terms

   !> Values of the first `nterm` terms of 1, x, y, xy, x^2, y^2, x^2 y,
   !! x y^2, x^2 y^2 at (x, y); nterm = 1 (constant), 3, 4, 8 or 9.
   pure subroutine fit_basis_xy(nterm, x, y, phi)
      integer, intent(in) :: nterm           !! number of terms
      real(dp), intent(in) :: x, y           !! local coordinates
      real(dp), intent(out) :: phi(MAX_TERMS) !! basis values; entries beyond nterm are zero
      real(dp) :: all(MAX_TERMS)
      all = [1.0_dp, x, y, x*y, x*x, y*y, x*x*y, x*y*y, x*x*y*y]
      phi = 0.0_dp
      phi(1:nterm) = all(1:nterm)
   end subroutine fit_basis_xy

   !> Least-squares fit of the `nterm`-term polynomial to the stresses
   !! sig(:, 1:npt) sampled at xy(:, 1:npt), in the local coordinates of the
   !! patch (centre, size h).  `ok` is false (coef zero) when there are fewer
   !! points than terms or the normal equations are singular to 1e-10 of
   !! their largest entry (points on a line for a 2-D polynomial, ...).
   pure subroutine patch_fit(nterm, npt, xy, sig, centre, h, coef, ok)
      integer, intent(in) :: nterm                 !! terms: 1, 3, 4, 8 or 9
      integer, intent(in) :: npt                   !! sampling points
      real(dp), intent(in) :: xy(2, npt)           !! their coordinates [length]
      real(dp), intent(in) :: sig(4, npt)          !! stresses there (xx, yy, xy, zz) [stress]
      real(dp), intent(in) :: centre(2)            !! centre of the patch [length]
      real(dp), intent(in) :: h                    !! size of the patch (> 0) [length]
      real(dp), intent(out) :: coef(MAX_TERMS, 4)  !! coefficients of each component
      logical, intent(out) :: ok                   !! the fit is determined
      real(dp) :: a(nterm, nterm), b(nterm, 4), phi(MAX_TERMS), row(nterm), rowb(4), f, amax
      integer :: ip, i, k, ipiv

      coef = 0.0_dp
      ok = npt >= nterm .and. nterm >= 1 .and. h > 0.0_dp
      if (.not. ok) return
      a = 0.0_dp
      b = 0.0_dp
      do ip = 1, npt
         call fit_basis_xy(nterm, (xy(1, ip) - centre(1))/h, (xy(2, ip) - centre(2))/h, phi)
         do i = 1, nterm
            a(:, i) = a(:, i) + phi(1:nterm)*phi(i)
            b(i, :) = b(i, :) + phi(i)*sig(:, ip)
         end do
      end do
      amax = maxval(abs(a))
      ! Gaussian elimination with partial pivoting
      do k = 1, nterm
         ipiv = k - 1 + maxloc(abs(a(k:nterm, k)), dim=1)
         if (abs(a(ipiv, k)) <= 1.0e-10_dp*amax) then
            ok = .false.
            return
         end if
         if (ipiv /= k) then
            row = a(k, :)
            a(k, :) = a(ipiv, :)
            a(ipiv, :) = row
            rowb = b(k, :)
            b(k, :) = b(ipiv, :)
            b(ipiv, :) = rowb
         end if
         do i = k + 1, nterm
            f = a(i, k)/a(k, k)
            a(i, k:nterm) = a(i, k:nterm) - f*a(k, k:nterm)
            b(i, :) = b(i, :) - f*b(k, :)
         end do
      end do
      do k = nterm, 1, -1
         b(k, :) = (b(k, :) - matmul(a(k, k + 1:nterm), b(k + 1:nterm, :)))/a(k, k)
      end do
      coef(1:nterm, :) = b
   end subroutine patch_fit

   !> The recovered stresses of a patch fit at the point xy.
   pure function patch_value(nterm, coef, centre, h, xy) result(sig)
      integer, intent(in) :: nterm                 !! terms of the fit
      real(dp), intent(in) :: coef(MAX_TERMS, 4)   !! its coefficients
      real(dp), intent(in) :: centre(2)            !! centre of the patch [length]
      real(dp), intent(in) :: h                    !! size of the patch [length]
      real(dp), intent(in) :: xy(2)                !! the point [length]
      real(dp) :: sig(4)                           !! (xx, yy, xy, zz) [stress]
      real(dp) :: phi(MAX_TERMS)
      call fit_basis_xy(nterm, (xy(1) - centre(1))/h, (xy(2) - centre(2))/h, phi)
      sig = matmul(phi(1:nterm), coef(1:nterm, :))
   end function patch_value

   !> s^T D^-1 s: twice the complementary energy density of the stress s
   !! (xx, yy, xy, zz) [stress].  Plane stress: the in-plane compliance;
   !! plane strain: the in-plane compliance of the plane-strain D (sig_zz is
   !! not independent); axisymmetric: the 3-D compliance with the hoop stress.
   pure real(dp) function stress_energy(ntype, young, poiss, s) result(w)
      integer, intent(in) :: ntype       !! 1 plane stress, 2 plane strain, 3 axisymmetric
      real(dp), intent(in) :: young      !! Young's modulus [stress]
      real(dp), intent(in) :: poiss      !! Poisson's ratio [-]
      real(dp), intent(in) :: s(4)       !! stress (xx, yy, xy, zz)
      select case (ntype)
      case (1)
         w = (s(1)**2 + s(2)**2 - 2.0_dp*poiss*s(1)*s(2) + 2.0_dp*(1.0_dp + poiss)*s(3)**2)/young
      case (2)
         w = ((1.0_dp - poiss**2)*(s(1)**2 + s(2)**2) - 2.0_dp*poiss*(1.0_dp + poiss)*s(1)*s(2) &
              + 2.0_dp*(1.0_dp + poiss)*s(3)**2)/young
      case default
         w = (s(1)**2 + s(2)**2 + s(4)**2 - 2.0_dp*poiss*(s(1)*s(2) + s(2)*s(4) + s(4)*s(1)) &
              + 2.0_dp*(1.0_dp + poiss)*s(3)**2)/young
      end select
   end function stress_energy

   !> Shape functions and volume weights (w det J thick, or w det J 2 pi r) at
   !! the points of the element's Gauss rule, in the order of the stress
   !! recovery (`solid2d::element_stresses`).  ierr: 0, the first point with
   !! det J <= 0, or -1 for an unsupported element or rule.
   pure subroutine gauss_volumes(ntype, nnode, elcod, thick, ngaus, ngp, shape_gp, dvol, ierr)
      integer, intent(in) :: ntype                   !! 1 plane stress, 2 plane strain, 3 axisymmetric
      integer, intent(in) :: nnode                   !! nodes per element
      real(dp), intent(in) :: elcod(2, nnode)        !! nodal coordinates [length]
      real(dp), intent(in) :: thick                  !! thickness, plane problems [length]
      integer, intent(in) :: ngaus                   !! Gauss rule, 0 = default
      integer, intent(out) :: ngp                    !! points of the rule
      real(dp), intent(out) :: shape_gp(nnode, max_gp) !! shape functions at the points
      real(dp), intent(out) :: dvol(max_gp)          !! volume weights [volume]
      integer, intent(out) :: ierr                   !! status
      real(dp) :: posgp(2, max_gp), weigp(max_gp), deriv(2, nnode), cartd(2, nnode), djacb, r
      logical :: ok
      integer :: ig

      shape_gp = 0.0_dp
      dvol = 0.0_dp
      ierr = 0
      call element_gauss_rule(nnode, ntype, ngaus, posgp, weigp, ngp)
      if (ngp == 0 .or. recovery_terms(nnode) == 0) then
         ierr = -1
         return
      end if
      do ig = 1, ngp
         call shape_functions(nnode, posgp(1, ig), posgp(2, ig), shape_gp(:, ig), deriv)
         call jacobian_2d(nnode, elcod, deriv, cartd, djacb, ok)
         if (.not. ok) then
            ierr = ig
            return
         end if
         if (ntype == 3) then
            r = dot_product(elcod(1, :), shape_gp(:, ig))
            dvol(ig) = weigp(ig)*djacb*two_pi*r
         else
            dvol(ig) = weigp(ig)*djacb*thick
         end if
      end do
   end subroutine gauss_volumes

   !> Energy-norm integrals of one element: err2 = ||sigma* - sigma_h||_E^2
   !! with sigma* interpolated from its nodal values by the element's shape
   !! functions, and ene2 = ||sigma_h||_E^2 (= ||u_h||_E^2 on the element),
   !! both by the element's Gauss rule, at whose points sigma_h is given.
   pure subroutine element_error_energy(ntype, nnode, elcod, young, poiss, thick, ngaus, sig_star, &
                                        sig_gp, err2, ene2, ierr)
      integer, intent(in) :: ntype                 !! 1 plane stress, 2 plane strain, 3 axisymmetric
      integer, intent(in) :: nnode                 !! nodes per element
      real(dp), intent(in) :: elcod(2, nnode)      !! nodal coordinates [length]
      real(dp), intent(in) :: young                !! Young's modulus [stress]
      real(dp), intent(in) :: poiss                !! Poisson's ratio [-]
      real(dp), intent(in) :: thick                !! thickness, plane problems [length]
      integer, intent(in) :: ngaus                 !! Gauss rule, 0 = default
      real(dp), intent(in) :: sig_star(4, nnode)   !! recovered stresses at the nodes [stress]
      real(dp), intent(in) :: sig_gp(:, :)         !! (4, ngp) FE stresses at the Gauss points [stress]
      real(dp), intent(out) :: err2                !! ||sigma* - sigma_h||_E^2 [energy]
      real(dp), intent(out) :: ene2                !! ||sigma_h||_E^2 [energy]
      integer, intent(out) :: ierr                 !! see gauss_volumes; -1 also for a sig_gp of the wrong size
      real(dp) :: shape_gp(nnode, max_gp), dvol(max_gp), s(4)
      integer :: ngp, ig

      err2 = 0.0_dp
      ene2 = 0.0_dp
      call gauss_volumes(ntype, nnode, elcod, thick, ngaus, ngp, shape_gp, dvol, ierr)
      if (ierr == 0 .and. size(sig_gp, 2) /= ngp) ierr = -1
      if (ierr /= 0) return
      do ig = 1, ngp
         s = matmul(sig_star, shape_gp(:, ig)) - sig_gp(:, ig)
         err2 = err2 + stress_energy(ntype, young, poiss, s)*dvol(ig)
         ene2 = ene2 + stress_energy(ntype, young, poiss, sig_gp(:, ig))*dvol(ig)
      end do
   end subroutine element_error_energy

end module error_estimator
