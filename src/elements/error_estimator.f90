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
   use elastic_law, only: d_matrix
   implicit none
   private

   public :: MAX_TERMS, recovery_terms, fit_basis_xy, patch_fit, patch_value, stress_energy, &
             gauss_volumes, element_error_energy, rule_shapes, point_stresses

   integer, parameter :: MAX_TERMS = 9   !! most terms of a recovery polynomial (Q9)
   integer, parameter :: MAX_NODE_E = 9  !! most nodes of an element (Q9)

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
   !! x y^2, x^2 y^2 at (x, y); nterm = 1 (constant), 3, 4, 8 or 9 (the
   !! entries beyond nterm are not set).
   pure subroutine fit_basis_xy(nterm, x, y, phi)
      integer, intent(in) :: nterm           !! number of terms
      real(dp), intent(in) :: x, y           !! local coordinates
      real(dp), intent(out) :: phi(MAX_TERMS) !! basis values; entries beyond nterm are undefined
      phi(1) = 1.0_dp
      if (nterm < 3) return
      phi(2) = x
      phi(3) = y
      if (nterm < 4) return
      phi(4) = x*y
      if (nterm < 8) return
      phi(5) = x*x
      phi(6) = y*y
      phi(7) = x*x*y
      phi(8) = x*y*y
      if (nterm < 9) return
      phi(9) = x*x*y*y
   end subroutine fit_basis_xy

   !> Least-squares fit of the `nterm`-term polynomial to the stresses
   !! sig(:, 1:npt) sampled at xy(:, 1:npt), in the local coordinates of the
   !! patch (centre, size h).  `ok` is false (coef zero) when there are fewer
   !! points than terms or the normal equations are singular to 1e-10 of
   !! their largest entry (points on a line for a 2-D polynomial, ...).
   !! The normal equations of all four components are solved together (one
   !! Cholesky factorization, four right-hand sides), in fixed-size work
   !! arrays: no allocation per patch.
   pure subroutine patch_fit(nterm, npt, xy, sig, centre, h, coef, ok)
      integer, intent(in) :: nterm                 !! terms: 1, 3, 4, 8 or 9
      integer, intent(in) :: npt                   !! sampling points
      real(dp), intent(in) :: xy(2, npt)           !! their coordinates [length]
      real(dp), intent(in) :: sig(4, npt)          !! stresses there (xx, yy, xy, zz) [stress]
      real(dp), intent(in) :: centre(2)            !! centre of the patch [length]
      real(dp), intent(in) :: h                    !! size of the patch (> 0) [length]
      real(dp), intent(out) :: coef(MAX_TERMS, 4)  !! coefficients of each component
      logical, intent(out) :: ok                   !! the fit is determined
      real(dp) :: a(MAX_TERMS, MAX_TERMS), b(4, MAX_TERMS), phi(MAX_TERMS), t(4), f, amax, hinv
      integer :: ip, i, k, l

      coef = 0.0_dp
      ok = npt >= nterm .and. nterm >= 1 .and. h > 0.0_dp
      if (.not. ok) return
      hinv = 1.0_dp/h
      if (nterm == 4) then
         call normal_bilinear(npt, xy, sig, centre, hinv, a, b)
      else
         a(1:nterm, 1:nterm) = 0.0_dp
         b(:, 1:nterm) = 0.0_dp
         do ip = 1, npt
            call fit_basis_xy(nterm, (xy(1, ip) - centre(1))*hinv, (xy(2, ip) - centre(2))*hinv, &
                              phi)
            do i = 1, nterm
               do k = i, nterm
                  a(k, i) = a(k, i) + phi(k)*phi(i)
               end do
               b(:, i) = b(:, i) + phi(i)*sig(:, ip)
            end do
         end do
      end if
      ! Cholesky factorization a = L L^T of the symmetric positive (semi)definite normal
      ! matrix (lower triangle, in place); a pivot at or below 1e-10 of the largest entry
      ! means the points do not determine the polynomial
      amax = 0.0_dp
      do i = 1, nterm
         amax = max(amax, maxval(abs(a(i:nterm, i))))
      end do
      do k = 1, nterm
         f = a(k, k)
         do l = 1, k - 1
            f = f - a(k, l)*a(k, l)
         end do
         if (f <= 1.0e-10_dp*amax) then
            ok = .false.
            return
         end if
         a(k, k) = sqrt(f)
         do i = k + 1, nterm
            f = a(i, k)
            do l = 1, k - 1
               f = f - a(i, l)*a(k, l)
            end do
            a(i, k) = f/a(k, k)
         end do
      end do
      ! L y = b, L^T x = y, the four components together
      do k = 1, nterm
         t = b(:, k)
         do l = 1, k - 1
            t = t - a(k, l)*b(:, l)
         end do
         b(:, k) = t/a(k, k)
      end do
      do k = nterm, 1, -1
         t = b(:, k)
         do l = k + 1, nterm
            t = t - a(l, k)*b(:, l)
         end do
         b(:, k) = t/a(k, k)
      end do
      coef(1:nterm, :) = transpose(b(:, 1:nterm))
   end subroutine patch_fit

   !> The normal equations of the bilinear fit {1, x, y, xy} (Q4), the lower
   !! triangle of a and the right-hand sides b, accumulated in scalars (the
   !! same sums, in the same order, as the general loop of patch_fit).
   pure subroutine normal_bilinear(npt, xy, sig, centre, hinv, a, b)
      integer, intent(in) :: npt                          !! sampling points
      real(dp), intent(in) :: xy(2, npt), sig(4, npt)     !! their coordinates and stresses
      real(dp), intent(in) :: centre(2), hinv             !! centre of the patch, 1 / its size
      real(dp), intent(inout) :: a(MAX_TERMS, MAX_TERMS)  !! normal matrix (lower triangle set)
      real(dp), intent(inout) :: b(4, MAX_TERMS)          !! right-hand sides
      real(dp) :: x, y, w, a11, a21, a31, a41, a22, a32, a42, a33, a43, a44
      real(dp) :: b1(4), b2(4), b3(4), b4(4)
      integer :: ip
      a11 = 0.0_dp
      a21 = 0.0_dp
      a31 = 0.0_dp
      a41 = 0.0_dp
      a22 = 0.0_dp
      a32 = 0.0_dp
      a42 = 0.0_dp
      a33 = 0.0_dp
      a43 = 0.0_dp
      a44 = 0.0_dp
      b1 = 0.0_dp
      b2 = 0.0_dp
      b3 = 0.0_dp
      b4 = 0.0_dp
      do ip = 1, npt
         x = (xy(1, ip) - centre(1))*hinv
         y = (xy(2, ip) - centre(2))*hinv
         w = x*y
         a11 = a11 + 1.0_dp
         a21 = a21 + x
         a31 = a31 + y
         a41 = a41 + w
         a22 = a22 + x*x
         a32 = a32 + y*x
         a42 = a42 + w*x
         a33 = a33 + y*y
         a43 = a43 + w*y
         a44 = a44 + w*w
         b1 = b1 + sig(:, ip)
         b2 = b2 + x*sig(:, ip)
         b3 = b3 + y*sig(:, ip)
         b4 = b4 + w*sig(:, ip)
      end do
      a(1:4, 1) = [a11, a21, a31, a41]
      a(2:4, 2) = [a22, a32, a42]
      a(3:4, 3) = [a33, a43]
      a(4, 4) = a44
      b(:, 1) = b1
      b(:, 2) = b2
      b(:, 3) = b3
      b(:, 4) = b4
   end subroutine normal_bilinear

   !> The recovered stresses of a patch fit at the point xy.
   pure function patch_value(nterm, coef, centre, h, xy) result(sig)
      integer, intent(in) :: nterm                 !! terms of the fit
      real(dp), intent(in) :: coef(MAX_TERMS, 4)   !! its coefficients
      real(dp), intent(in) :: centre(2)            !! centre of the patch [length]
      real(dp), intent(in) :: h                    !! size of the patch [length]
      real(dp), intent(in) :: xy(2)                !! the point [length]
      real(dp) :: sig(4)                           !! (xx, yy, xy, zz) [stress]
      real(dp) :: phi(MAX_TERMS)
      integer :: k
      call fit_basis_xy(nterm, (xy(1) - centre(1))/h, (xy(2) - centre(2))/h, phi)
      sig = phi(1)*coef(1, :)
      do k = 2, nterm
         sig = sig + phi(k)*coef(k, :)
      end do
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
      integer, intent(in) :: ntype                   !! 1 plane stress, 2 plane strain, 3 axisym.
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

   !> Shape functions, their natural derivatives and the weights at the
   !! points of an element's Gauss rule (`quadrature::element_gauss_rule`):
   !! the same for every element of a type, so computed once per type.
   pure subroutine rule_shapes(nnode, ntype, ngaus, ngp, shape_gp, deriv_gp, weigp)
      integer, intent(in) :: nnode                      !! nodes per element
      integer, intent(in) :: ntype                      !! analysis type
      integer, intent(in) :: ngaus                      !! Gauss rule, 0 = default
      integer, intent(out) :: ngp                       !! points (0: no such rule or element)
      real(dp), intent(out) :: shape_gp(nnode, max_gp)  !! shape functions at the points
      real(dp), intent(out) :: deriv_gp(2, nnode, max_gp) !! dN/ds, dN/dt at the points
      real(dp), intent(out) :: weigp(max_gp)            !! weights
      real(dp) :: posgp(2, max_gp)
      integer :: ig
      shape_gp = 0.0_dp
      deriv_gp = 0.0_dp
      call element_gauss_rule(nnode, ntype, ngaus, posgp, weigp, ngp)
      if (recovery_terms(nnode) == 0) ngp = 0
      do ig = 1, ngp
         call shape_functions(nnode, posgp(1, ig), posgp(2, ig), shape_gp(:, ig), &
                              deriv_gp(:, :, ig))
      end do
   end subroutine rule_shapes

   !> Stresses sigma = D B u (xx, yy, xy, zz) and positions at given points
   !! of one element (shape functions and natural derivatives from
   !! `rule_shapes`), as `solid2d::element_stresses` gives them at its Gauss
   !! points: sig_zz = nu (sig_xx + sig_yy) in plane strain, the hoop stress
   !! from u_r / r in axisymmetry.  ierr: 0, or the first point with det J <= 0
   !! or (axisymmetric) r <= 0.
   pure subroutine point_stresses(ntype, nnode, elcod, young, poiss, eldis, npt, shape_pt, &
                                 deriv_pt, xy, sig, ierr)
      integer, intent(in) :: ntype                      !! 1 plane stress, 2 plane strain, 3 axisym.
      integer, intent(in) :: nnode                      !! nodes per element
      real(dp), intent(in) :: elcod(2, nnode)           !! nodal coordinates [length]
      real(dp), intent(in) :: young                     !! Young's modulus [stress]
      real(dp), intent(in) :: poiss                     !! Poisson's ratio [-]
      real(dp), intent(in) :: eldis(2, nnode)           !! nodal displacements [length]
      integer, intent(in) :: npt                        !! points
      real(dp), intent(in) :: shape_pt(nnode, npt)      !! shape functions at the points
      real(dp), intent(in) :: deriv_pt(2, nnode, npt)   !! natural derivatives at the points
      real(dp), intent(out) :: xy(2, npt)               !! positions of the points [length]
      real(dp), intent(out) :: sig(4, npt)              !! stresses there [stress]
      integer, intent(out) :: ierr                      !! status
      real(dp) :: dmatx(4, 4), cartd(2, MAX_NODE_E), djacb, gradu(2, 2), eps(4)
      logical :: ok
      integer :: ip, k
      ierr = 0
      xy = 0.0_dp
      sig = 0.0_dp
      call d_matrix(ntype, young, poiss, dmatx)
      do ip = 1, npt
         xy(:, ip) = 0.0_dp
         do k = 1, nnode
            xy(:, ip) = xy(:, ip) + elcod(:, k)*shape_pt(k, ip)
         end do
         call jacobian_2d(nnode, elcod, deriv_pt(:, :, ip), cartd(:, 1:nnode), djacb, ok)
         if (.not. ok .or. (ntype == 3 .and. xy(1, ip) <= 0.0_dp)) then
            ierr = ip
            return
         end if
         gradu = 0.0_dp                                   ! gradu(i, j) = d u_i / d x_j
         do k = 1, nnode
            gradu(:, 1) = gradu(:, 1) + eldis(:, k)*cartd(1, k)
            gradu(:, 2) = gradu(:, 2) + eldis(:, k)*cartd(2, k)
         end do
         eps = [gradu(1, 1), gradu(2, 2), gradu(1, 2) + gradu(2, 1), 0.0_dp]
         if (ntype == 3) eps(4) = dot_product(eldis(1, :), shape_pt(:, ip))/xy(1, ip)
         sig(:, ip) = matmul(dmatx, eps)
         if (ntype == 2) sig(4, ip) = poiss*(sig(1, ip) + sig(2, ip))
      end do
   end subroutine point_stresses

   !> Energy-norm integrals of one element: err2 = ||sigma* - sigma_h||_E^2
   !! with sigma* interpolated from its nodal values by the element's shape
   !! functions, and ene2 = ||sigma_h||_E^2 (= ||u_h||_E^2 on the element),
   !! both by the element's Gauss rule (shape functions, derivatives and
   !! weights from `rule_shapes`), at whose points sigma_h is given.
   pure subroutine element_error_energy(ntype, nnode, elcod, young, poiss, thick, ngp, shape_gp, &
                                        deriv_gp, weigp, sig_star, sig_gp, err2, ene2, ierr)
      integer, intent(in) :: ntype                 !! 1 plane stress, 2 plane strain, 3 axisymmetric
      integer, intent(in) :: nnode                 !! nodes per element
      real(dp), intent(in) :: elcod(2, nnode)      !! nodal coordinates [length]
      real(dp), intent(in) :: young                !! Young's modulus [stress]
      real(dp), intent(in) :: poiss                !! Poisson's ratio [-]
      real(dp), intent(in) :: thick                !! thickness, plane problems [length]
      integer, intent(in) :: ngp                   !! points of the rule
      real(dp), intent(in) :: shape_gp(nnode, ngp) !! shape functions at them
      real(dp), intent(in) :: deriv_gp(2, nnode, ngp) !! natural derivatives at them
      real(dp), intent(in) :: weigp(ngp)           !! weights
      real(dp), intent(in) :: sig_star(4, nnode)   !! recovered stresses at the nodes [stress]
      real(dp), intent(in) :: sig_gp(4, ngp)       !! FE stresses at the Gauss points [stress]
      real(dp), intent(out) :: err2                !! ||sigma* - sigma_h||_E^2 [energy]
      real(dp), intent(out) :: ene2                !! ||sigma_h||_E^2 [energy]
      integer, intent(out) :: ierr                 !! 0, or the first point with det J <= 0
      real(dp) :: s(4), xjacm(2, 2), djacb, dvol
      integer :: ig, k

      err2 = 0.0_dp
      ene2 = 0.0_dp
      ierr = 0
      do ig = 1, ngp
         ! the Jacobian and sigma* at the point, summed node by node (no array temporaries)
         xjacm = 0.0_dp
         s = -sig_gp(:, ig)
         do k = 1, nnode
            xjacm(:, 1) = xjacm(:, 1) + deriv_gp(:, k, ig)*elcod(1, k)
            xjacm(:, 2) = xjacm(:, 2) + deriv_gp(:, k, ig)*elcod(2, k)
            s = s + sig_star(:, k)*shape_gp(k, ig)
         end do
         djacb = xjacm(1, 1)*xjacm(2, 2) - xjacm(1, 2)*xjacm(2, 1)
         if (.not. djacb > 0.0_dp) then
            ierr = ig
            return
         end if
         if (ntype == 3) then
            dvol = weigp(ig)*djacb*two_pi*dot_product(elcod(1, :), shape_gp(:, ig))
         else
            dvol = weigp(ig)*djacb*thick
         end if
         err2 = err2 + stress_energy(ntype, young, poiss, s)*dvol
         ene2 = ene2 + stress_energy(ntype, young, poiss, sig_gp(:, ig))*dvol
      end do
   end subroutine element_error_energy

end module error_estimator
