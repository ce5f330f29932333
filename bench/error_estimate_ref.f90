!> A frozen copy of the error estimate as it was before its speed-up (modules
!! error_estimator and error_estimate of the commit before it, renamed; its long lines
!! wrapped and the contact interface's indicator, which the benchmark does not use, left
!! out): bench/bench_estimate.F90 times it beside the current one in the same run and
!! compares their values.
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
module error_estimator_ref
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
            do k = i, nterm
               a(k, i) = a(k, i) + phi(k)*phi(i)
            end do
            b(i, :) = b(i, :) + phi(i)*sig(:, ip)
         end do
      end do
      do i = 1, nterm
         a(i, i + 1:nterm) = a(i + 1:nterm, i)
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
      real(dp) :: dmatx(4, 4), cartd(2, nnode), djacb, gradu(2, 2), eps(4)
      logical :: ok
      integer :: ip
      ierr = 0
      xy = 0.0_dp
      sig = 0.0_dp
      call d_matrix(ntype, young, poiss, dmatx)
      do ip = 1, npt
         xy(:, ip) = matmul(elcod, shape_pt(:, ip))
         call jacobian_2d(nnode, elcod, deriv_pt(:, :, ip), cartd, djacb, ok)
         if (.not. ok .or. (ntype == 3 .and. xy(1, ip) <= 0.0_dp)) then
            ierr = ip
            return
         end if
         gradu = matmul(eldis, transpose(cartd))          ! gradu(i, j) = d u_i / d x_j
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
      integer :: ig

      err2 = 0.0_dp
      ene2 = 0.0_dp
      ierr = 0
      do ig = 1, ngp
         xjacm = matmul(deriv_gp(:, :, ig), transpose(elcod))
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
         s = matmul(sig_star, shape_gp(:, ig)) - sig_gp(:, ig)
         err2 = err2 + stress_energy(ntype, young, poiss, s)*dvol
         ene2 = ene2 + stress_energy(ntype, young, poiss, sig_gp(:, ig))*dvol
      end do
   end subroutine element_error_energy

end module error_estimator_ref
!> A posteriori error estimate of a step: the recovery-based (Zienkiewicz-Zhu)
!! estimate of the bodies' discretization error in the energy norm, element
!! by element, and an indicator of how well the contact pairs resolve the
!! contact pressure.
!!
!! Bodies.  The recovered stresses sigma* come from superconvergent patch
!! recovery: around every corner node of the mesh, the elements that share
!! it (the node's patch; elements of another material form a patch of their
!! own, since the stresses jump there) fit one polynomial to their sampled
!! stresses (kernels in `error_estimator`): the Gauss-point stresses of T3
!! and Q4, and for Q8 and Q9 the stresses at their 2 x 2 Gauss points, the
!! superconvergent points of the quadratic elements (ZZ Part 1; sampled at
!! the 3 x 3 points of their stiffness rule, the error of Lame's cylinder is
!! underestimated by 15 - 30 %).  Every patch gives its polynomial's value at
!! all nodes of its elements, and the values a node receives (one from each
!! patch that holds it) are averaged (per material).  Interior patches come
!! first: a patch on the boundary fits from one side and, on a curved
!! boundary, from points near one line.  A node that no interior patch
!! reaches takes the patches around it, boundary ones too, with the
!! element's polynomial or, where their points do not determine it (a corner
!! patch of one T3, a strip one element thick), the linear and then the
!! constant one.  sigma* is interpolated in each element by its
!! shape functions, and
!!
!!     ||e*||_E,e^2 = int_e (sigma* - sigma_h)^T D^-1 (sigma* - sigma_h) dV,
!!     eta_e = ||e*||_E,e / sqrt(||u_h||_E^2 + ||e*||_E^2),
!!     eta   = ||e*||_E / sqrt(||u_h||_E^2 + ||e*||_E^2) = sqrt(sum_e eta_e^2),
!!
!! with the norms of the whole model in the denominators (error_indicator
!! and estimated_error of the body fields record).  The field is exact where
!! the FE stresses are a polynomial of the recovery's degree, so a patch test
!! gives zero.
!!
!! Interface.  The pairs of every interface are ordered along it (by their
!! position projected on the interface's mean tangent); a pair's resolution
!! indicator is the larger jump of the contact pressure to its two
!! neighbours, relative to the interface's peak pressure: ~ |dp/ds| s / p_max
!! for a pair spacing s, and at the edge of the contact zone the pressure
!! of the last closed pair (the edge lies inside one spacing).  The contact
!! zone of an interface is the range of its closed pairs; its width (2a; a in a half model) runs
!! to the midpoints between the outermost closed pairs and their open
!! neighbours (to the outermost pair itself where the zone reaches the end of
!! the interface).
!!
!! Ref: Zienkiewicz & Zhu, IJNME 33 (1992) 1331-1364 (Part 1, the recovery)
!!      and 1365-1382 (Part 2, error estimates).
module error_estimate_ref
   use kinds, only: dp
   use errors, only: status_t, STAT_JACOBIAN
   use strings, only: itoa
   use model, only: model_t, MAX_NODE
   use records, only: body_fields_t, contact_fields_t
   use topology, only: corner_count
   use error_estimator_ref, only: MAX_TERMS, recovery_terms, patch_fit, patch_value, &
                                  element_error_energy, &
                              rule_shapes, point_stresses
   use quadrature, only: max_gp
   implicit none
   private
   public :: estimate_error_ref

   !> Shape functions, natural derivatives and weights of one Gauss rule of
   !! one element type (the same for every element of the type).
   type :: rule_t
      integer :: ngp = 0
      real(dp), allocatable :: shp(:, :)       !! (nnode, ngp)
      real(dp), allocatable :: der(:, :, :)    !! (2, nnode, ngp)
      real(dp), allocatable :: w(:)            !! (ngp)
   end type rule_t

contains

   !> The error estimate of the step whose stresses the body fields hold
   !! (error_indicator, estimated_error, error_norm, energy_norm), and the
   !! interface's resolution indicators in the contact fields (if it has pairs).
   subroutine estimate_error_ref(m, body, cf, status)
      type(model_t), intent(in) :: m
      type(body_fields_t), intent(inout) :: body
      type(contact_fields_t), intent(inout) :: cf
      type(status_t), intent(inout) :: status
      real(dp), allocatable :: sstar(:, :, :), e2(:), u2(:)
      real(dp) :: elcod(2, MAX_NODE), total
      type(rule_t) :: rules(MAX_NODE)
      integer :: ie, nn, imat, ierr

      call recover_patch_stresses(m, body, sstar, status)
      if (.not. status%ok()) return
      call element_rules(m, m%ngaus, rules)
      allocate (e2(m%nelem), u2(m%nelem))
      do ie = 1, m%nelem
         nn = m%nnode_e(ie)
         imat = m%matno(ie)
         elcod(:, 1:nn) = m%coord(:, m%lnods(1:nn, ie))
         ierr = -1
         if (rules(nn)%ngp == body%gp_start(ie + 1) - body%gp_start(ie)) then
            call element_error_energy(m%ntype, nn, elcod(:, 1:nn), m%mats(imat)%young, &
                                      m%mats(imat)%poiss, m%mats(imat)%thick, rules(nn)%ngp, &
                                      rules(nn)%shp, rules(nn)%der, rules(nn)%w, &
                                      sstar(:, 1:nn, ie), &
                                      body%sig_gp(:, body%gp_start(ie):body%gp_start(ie + 1) - 1), &
                                      e2(ie), u2(ie), ierr)
         end if
         if (ierr /= 0) then
            call status%set(STAT_JACOBIAN, 'element '//itoa(ie)// &
                            ' (error estimate): no valid Gauss rule or det J <= 0')
            return
         end if
      end do
      if (allocated(body%error_indicator)) then
         if (size(body%error_indicator) /= m%nelem) deallocate (body%error_indicator)
      end if
      if (.not. allocated(body%error_indicator)) allocate (body%error_indicator(m%nelem))
      total = sum(u2) + sum(e2)
      if (total > 0.0_dp) then
         body%error_indicator = sqrt(e2/total)
         body%estimated_error = sqrt(sum(e2)/total)
      else
         body%error_indicator = 0.0_dp
         body%estimated_error = 0.0_dp
      end if
      body%error_norm = sqrt(sum(e2))
      body%energy_norm = sqrt(sum(u2))
      body%estimated = .true.
   end subroutine estimate_error_ref

   !> Recovered stresses sigma* at the nodes of every element, (4, nnode of
   !! the largest element, nelem), by superconvergent patch recovery from the Gauss-point stresses
   !! of the body fields (see the module header).
   subroutine recover_patch_stresses(m, body, sstar, status)
      type(model_t), intent(in) :: m
      type(body_fields_t), intent(in) :: body
      real(dp), allocatable, intent(out) :: sstar(:, :, :)
      type(status_t), intent(inout) :: status
      integer, allocatable :: slot(:, :), pstart(:), pelem(:), matslot(:, :), sstart(:)
      real(dp), allocatable :: acc(:, :), acc2(:, :), sxy(:, :), ssig(:, :), wxy(:, :), wsg(:, :)
      integer, allocatable :: cnt(:), cnt2(:), seen(:)
      integer :: ie, k, ip, nslot, nmat, pass, maxpt, maxnn, npatch

      call sample_stresses(m, body, sstart, sxy, ssig, status)
      if (.not. status%ok()) return

      ! one recovered value per (node, material): the slots
      nmat = max(1, m%nmats)
      if (m%nelem > 0) nmat = max(nmat, maxval(m%matno))
      maxnn = 1
      if (m%nelem > 0) maxnn = maxval(m%nnode_e(1:m%nelem))
      allocate (matslot(nmat, m%npoin), slot(maxnn, m%nelem))
      matslot = 0
      slot = 0
      nslot = 0
      do ie = 1, m%nelem
         do k = 1, m%nnode_e(ie)
            ip = m%lnods(k, ie)
            if (matslot(m%matno(ie), ip) == 0) then
               nslot = nslot + 1
               matslot(m%matno(ie), ip) = nslot
            end if
            slot(k, ie) = matslot(m%matno(ie), ip)
         end do
      end do
      deallocate (matslot)
      call corner_patches(m, pstart, pelem)
      ! work arrays for the largest patch
      maxpt = 1
      do ip = 1, m%npoin
         k = 0
         do ie = pstart(ip), pstart(ip + 1) - 1
            k = k + sstart(pelem(ie) + 1) - sstart(pelem(ie))
         end do
         maxpt = max(maxpt, k)
      end do
      allocate (wxy(2, maxpt), wsg(4, maxpt))
      allocate (acc(4, nslot), cnt(nslot), acc2(4, nslot), cnt2(nslot), seen(nslot))
      seen = 0
      npatch = 0
      acc = 0.0_dp
      cnt = 0
      acc2 = 0.0_dp
      cnt2 = 0
      ! pass 1: the interior patches with the elements' polynomial; pass 2: the
      ! slots no interior patch reached, from the patches around them (boundary
      ! ones too), with the elements' polynomial or, failing that, a smaller one
      do pass = 1, 2
         do ip = 1, m%npoin
            if (pstart(ip + 1) == pstart(ip)) cycle
            call fit_node_patch(ip, pelem(pstart(ip):pstart(ip + 1) - 1), pass)
         end do
      end do
      ! (4, nnode, nelem) with nnode the largest element's: entries beyond an element's nodes unused
      allocate (sstar(4, maxnn, m%nelem))
      do ie = 1, m%nelem
         do k = 1, m%nnode_e(ie)
            if (cnt(slot(k, ie)) > 0) then
               sstar(:, k, ie) = acc(:, slot(k, ie))/cnt(slot(k, ie))
            else if (cnt2(slot(k, ie)) > 0) then
               sstar(:, k, ie) = acc2(:, slot(k, ie))/cnt2(slot(k, ie))
            else
               sstar(:, k, ie) = body%sig_nd(:, m%lnods(k, ie))
            end if
         end do
      end do

   contains

      !> Fit the patch of corner node ip (its elements pel), one material at a
      !! time, and add the values at the elements' nodes.  Pass 1 fits only
      !! interior patches (every edge at ip shared by two elements of the
      !! material): a boundary patch fits from one side and, on a curved
      !! boundary, from points near one line, where its polynomial is nearly
      !! undetermined.
      subroutine fit_node_patch(ip, pel, pass)
         integer, intent(in) :: ip, pel(:), pass
         real(dp) :: coef(MAX_TERMS, 4), h, centre(2)
         integer :: imat, j, ie, k, n, npt, g0, g1, nterm, t, tries(3)
         logical :: ok, need
         centre = m%coord(:, ip)
         do j = 1, size(pel)
            imat = m%matno(pel(j))
            ! each material once: at its first element in the patch
            if (j > 1) then
               if (any(m%matno(pel(1:j - 1)) == imat)) cycle
            end if
            if (pass == 2) then
               need = .false.
               do k = j, size(pel)
                  ie = pel(k)
                  if (m%matno(ie) /= imat) cycle
                  if (any(cnt(slot(1:m%nnode_e(ie), ie)) == 0)) need = .true.
               end do
               if (.not. need) cycle
            else
               do k = j, size(pel)
                  ie = pel(k)
                  if (m%matno(ie) /= imat) cycle
                  if (.not. edges_shared(ip, ie, pel, imat)) exit
               end do
               if (k <= size(pel)) cycle
            end if
            npt = 0
            h = 0.0_dp
            nterm = MAX_TERMS
            do k = j, size(pel)
               ie = pel(k)
               if (m%matno(ie) /= imat) cycle
               nterm = min(nterm, recovery_terms(m%nnode_e(ie)))
               do n = 1, m%nnode_e(ie)
                  h = max(h, abs(m%coord(1, m%lnods(n, ie)) - centre(1)), &
                          abs(m%coord(2, m%lnods(n, ie)) - centre(2)))
               end do
               g0 = sstart(ie)
               g1 = sstart(ie + 1) - 1
               wxy(:, npt + 1:npt + g1 - g0 + 1) = sxy(:, g0:g1)
               wsg(:, npt + 1:npt + g1 - g0 + 1) = ssig(:, g0:g1)
               npt = npt + g1 - g0 + 1
            end do
            tries = [nterm, 3, 1]
            ok = .false.
            do t = 1, merge(1, 3, pass == 1)
               if (t > 1 .and. tries(t) >= nterm) cycle
               call patch_fit(tries(t), npt, wxy(:, 1:npt), wsg(:, 1:npt), centre, h, coef, ok)
               if (ok) exit
            end do
            if (.not. ok) cycle
            npatch = npatch + 1
            do k = j, size(pel)
               ie = pel(k)
               if (m%matno(ie) /= imat) cycle
               call add_values(ie, tries(t), coef, centre, h, pass)
            end do
         end do
      end subroutine fit_node_patch

      !> Both corner edges of element ie at its corner node ip are shared with
      !! another element of material imat of the patch pel.
      logical function edges_shared(ip, ie, pel, imat) result(shared)
         integer, intent(in) :: ip, ie, pel(:), imat
         integer :: nc, kc, side, other, k, ke, nce
         nc = corner_count(m%nnode_e(ie))
         kc = findloc(m%lnods(1:nc, ie), ip, 1)
         shared = .true.
         do side = -1, 1, 2
            other = m%lnods(modulo(kc - 1 + side, nc) + 1, ie)
            shared = .false.
            do k = 1, size(pel)
               ke = pel(k)
               if (ke == ie .or. m%matno(ke) /= imat) cycle
               nce = corner_count(m%nnode_e(ke))
               if (any(m%lnods(1:nce, ke) == other)) then
                  shared = .true.
                  exit
               end if
            end do
            if (.not. shared) return
         end do
      end function edges_shared

      !> The patch's values at the nodes of element ie, each node once per
      !! patch (npatch numbers the fitted patches).
      subroutine add_values(ie, nterm, coef, centre, h, pass)
         integer, intent(in) :: ie, nterm, pass
         real(dp), intent(in) :: coef(MAX_TERMS, 4), centre(2), h
         integer :: k, is
         do k = 1, m%nnode_e(ie)
            is = slot(k, ie)
            if (seen(is) == npatch) cycle
            seen(is) = npatch
            if (pass == 1) then
               acc(:, is) = acc(:, is) + patch_value(nterm, coef, centre, h, &
                                                     m%coord(:, m%lnods(k, ie)))
               cnt(is) = cnt(is) + 1
            else if (cnt(is) == 0) then
               acc2(:, is) = acc2(:, is) + patch_value(nterm, coef, centre, h, &
                                                       m%coord(:, m%lnods(k, ie)))
               cnt2(is) = cnt2(is) + 1
            end if
         end do
      end subroutine add_values
   end subroutine recover_patch_stresses

   !> The patches: the elements around every corner node, in CSR form
   !! (elements pelem(pstart(ip) : pstart(ip + 1) - 1) hold node ip as a corner).
   subroutine corner_patches(m, pstart, pelem)
      type(model_t), intent(in) :: m
      integer, allocatable, intent(out) :: pstart(:), pelem(:)
      integer, allocatable :: cnt(:)
      integer :: ie, k, ip
      allocate (pstart(m%npoin + 1))
      pstart = 0
      do ie = 1, m%nelem
         do k = 1, corner_count(m%nnode_e(ie))
            pstart(m%lnods(k, ie) + 1) = pstart(m%lnods(k, ie) + 1) + 1
         end do
      end do
      pstart(1) = 1
      do ip = 1, m%npoin
         pstart(ip + 1) = pstart(ip + 1) + pstart(ip)
      end do
      allocate (pelem(pstart(m%npoin + 1) - 1), cnt(m%npoin))
      cnt = 0
      do ie = 1, m%nelem
         do k = 1, corner_count(m%nnode_e(ie))
            ip = m%lnods(k, ie)
            pelem(pstart(ip) + cnt(ip)) = ie
            cnt(ip) = cnt(ip) + 1
         end do
      end do
      deallocate (cnt)
   end subroutine corner_patches

   !> The stresses the patches fit, element by element (sstart: first sample
   !! of each element): the Gauss-point stresses of the body fields, except
   !! for Q8 and Q9 with a rule other than 2 x 2, which are sampled at their
   !! 2 x 2 Gauss points from the displacements.
   subroutine sample_stresses(m, body, sstart, sxy, ssig, status)
      type(model_t), intent(in) :: m
      type(body_fields_t), intent(in) :: body
      integer, allocatable, intent(out) :: sstart(:)
      real(dp), allocatable, intent(out) :: sxy(:, :), ssig(:, :)
      type(status_t), intent(inout) :: status
      type(rule_t) :: r2(MAX_NODE)
      real(dp) :: elcod(2, MAX_NODE), eldis(2, MAX_NODE)
      integer :: ie, nn, ngp, ierr, imat
      logical, allocatable :: own(:)
      allocate (sstart(m%nelem + 1), own(m%nelem))
      sstart(1) = 1
      do ie = 1, m%nelem
         ngp = body%gp_start(ie + 1) - body%gp_start(ie)
         own(ie) = m%nnode_e(ie) < 8 .or. ngp == 4
         sstart(ie + 1) = sstart(ie) + merge(ngp, 4, own(ie))
      end do
      allocate (sxy(2, sstart(m%nelem + 1) - 1), ssig(4, sstart(m%nelem + 1) - 1))
      if (.not. all(own)) call element_rules(m, 2, r2)
      do ie = 1, m%nelem
         if (own(ie)) then
            associate (g0 => body%gp_start(ie), g1 => body%gp_start(ie + 1) - 1)
               sxy(:, sstart(ie):sstart(ie + 1) - 1) = body%xygp(:, g0:g1)
               ssig(:, sstart(ie):sstart(ie + 1) - 1) = body%sig_gp(:, g0:g1)
            end associate
            cycle
         end if
         nn = m%nnode_e(ie)
         imat = m%matno(ie)
         elcod(:, 1:nn) = m%coord(:, m%lnods(1:nn, ie))
         eldis(:, 1:nn) = body%disp(:, m%lnods(1:nn, ie))
         ierr = -1
         if (r2(nn)%ngp == 4) then
            call point_stresses(m%ntype, nn, elcod(:, 1:nn), m%mats(imat)%young, &
                                m%mats(imat)%poiss, eldis(:, 1:nn), 4, r2(nn)%shp, r2(nn)%der, &
                                sxy(:, sstart(ie):sstart(ie) + 3), &
                                ssig(:, sstart(ie):sstart(ie) + 3), ierr)
         end if
         if (ierr /= 0) then
            call status%set(STAT_JACOBIAN, 'element '//itoa(ie)// &
                            ' (error estimate): its 2 x 2 Gauss points fail')
            return
         end if
      end do
   end subroutine sample_stresses

   !> The Gauss rule `ngaus` of every element type of the model.
   subroutine element_rules(m, ngaus, rules)
      type(model_t), intent(in) :: m
      integer, intent(in) :: ngaus
      type(rule_t), intent(out) :: rules(MAX_NODE)
      real(dp) :: shp(MAX_NODE, max_gp), der(2, MAX_NODE, max_gp), w(max_gp)
      integer :: nn, ngp
      do nn = 1, MAX_NODE
         if (recovery_terms(nn) == 0) cycle
         if (.not. any(m%nnode_e(1:m%nelem) == nn)) cycle
         call rule_shapes(nn, m%ntype, ngaus, ngp, shp(1:nn, :), der(:, 1:nn, :), w)
         rules(nn)%ngp = ngp
         rules(nn)%shp = shp(1:nn, 1:ngp)
         rules(nn)%der = der(:, 1:nn, 1:ngp)
         rules(nn)%w = w(1:ngp)
      end do
   end subroutine element_rules

end module error_estimate_ref
