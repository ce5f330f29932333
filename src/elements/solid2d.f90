!> The 2-D isoparametric solid elements: stiffness, loads, stresses.
!!
!! One set of routines serves every element (codes 303, 404, 408, 409,
!! selected by the node count `nnode`) and every analysis type (`ntype`
!! 1 plane stress, 2 plane strain, 3 axisymmetric with x = r, y = z).
!!
!! Integration weight: `thick` for plane problems; 2 pi r for axisymmetry
!! (full ring, `thick` ignored), so that forces are total ring forces.
!! No routine divides by r: the hoop strain u/r is evaluated only at Gauss
!! points, which are strictly inside the element, and a Gauss point with
!! r <= 0 (element crossing the axis) is reported as an error.
!!
!! Status `ierr` of the element routines:
!!  * 0 - success;
!!  * k > 0 - det J is not positive at Gauss point k (first such point);
!!  * `solid_bad_element` (-1) - unsupported `nnode`, `ntype` or `ngaus`
!!    (or an `estif` of the wrong shape);
!!  * `solid_bad_radius` (-2) - axisymmetric Gauss point with r <= 0.
!! On error the output arrays are zero.
!!
!! Ref: Hinton & Owen, *Finite Element Programming* (1977), routine STIFFP;
!!      Owen & Hinton, *Finite Elements in Plasticity* (1980), routine LOADPS;
!!      Zienkiewicz & Taylor, *The Finite Element Method*, vol. 1
!!      (plane and axisymmetric elasticity, equivalent nodal forces,
!!      stress recovery).
module solid2d
   use kinds, only: dp, two_pi
   use quadrature, only: max_gp, element_gauss_rule, gauss_legendre
   use shape_2d, only: shape_functions, edge_shape, node_natural_coords, element_code
   use kinematics_2d, only: jacobian_2d, jacobian_determinant, b_matrix
   use elastic_law, only: d_matrix
   implicit none
   private

   public :: element_stiffness, element_stresses, element_internal_force, edge_load, &
             body_load, min_jacobian, solid_bad_element, solid_bad_radius, edge_ngaus

   integer, parameter :: solid_bad_element = -1   !! unsupported nnode, ntype or ngaus
   integer, parameter :: solid_bad_radius = -2    !! axisymmetric Gauss point with r <= 0
   !> Gauss points along an edge: degree 9, exact for a quadratic edge with
   !! a quadratic traction and the 2 pi r weight (degree 7).
   integer, parameter :: edge_ngaus = 5

contains

   !> Element stiffness matrix K = int B^T D B dV (STIFFP).
   !!
   !! The upper triangle is integrated and mirrored, so `estif` is exactly
   !! symmetric.  `estif` is assumed-shape so that a caller may pass a
   !! section of a larger work array without a copy; its shape must be
   !! (2*nnode, 2*nnode), otherwise `ierr = solid_bad_element`.
   !!
   !! Ref: Hinton & Owen (1977), STIFFP; Zienkiewicz & Taylor, vol. 1
   !!      (element stiffness K = int B^T D B dV).
   pure subroutine element_stiffness(ntype, nnode, elcod, young, poiss, thick, ngaus, estif, ierr)
      integer, intent(in) :: ntype                     !! 1 plane stress, 2 plane
                                                       !! strain, 3 axisymmetric
      integer, intent(in) :: nnode                     !! nodes per element: 3, 4, 8 or 9
      real(dp), intent(in) :: elcod(2, nnode)          !! nodal coordinates [length]
      real(dp), intent(in) :: young                    !! Young's modulus [stress]
      real(dp), intent(in) :: poiss                    !! Poisson's ratio [-]
      real(dp), intent(in) :: thick                    !! thickness, plane problems [length]
      integer, intent(in) :: ngaus                     !! Gauss rule, 0 = default
      real(dp), intent(out) :: estif(:, :)             !! stiffness, shape (2*nnode,
                                                       !! 2*nnode) [force/length]
      integer, intent(out) :: ierr                     !! status, see module header
      real(dp) :: posgp(2, max_gp), weigp(max_gp), dmatx(4, 4)
      real(dp) :: shape(nnode), cartd(2, nnode), bmatx(4, 2*nnode), dbmat(4, 2*nnode)
      real(dp) :: xy(2), dvolu
      integer :: ngp, igaus, ievab, jevab, nevab

      estif = 0.0_dp
      nevab = 2*nnode
      call prepare_rule(ntype, nnode, ngaus, posgp, weigp, ngp, ierr)
      if (size(estif, 1) /= nevab .or. size(estif, 2) /= nevab) ierr = solid_bad_element
      if (ierr /= 0) return
      call d_matrix(ntype, young, poiss, dmatx)
      do igaus = 1, ngp
         call gauss_point(ntype, nnode, elcod, posgp(:, igaus), weigp(igaus), thick, &
                          shape, cartd, xy, dvolu, igaus, ierr)
         if (ierr /= 0) then
            estif = 0.0_dp
            return
         end if
         call b_matrix(ntype, nnode, shape, cartd, xy(1), bmatx)
         dbmat = matmul(dmatx, bmatx)
         do jevab = 1, nevab
            do ievab = 1, jevab
               estif(ievab, jevab) = estif(ievab, jevab) + &
                                     dot_product(bmatx(:, ievab), dbmat(:, jevab))*dvolu
            end do
         end do
      end do
      do jevab = 1, nevab
         do ievab = jevab + 1, nevab
            estif(ievab, jevab) = estif(jevab, ievab)
         end do
      end do
   end subroutine element_stiffness

   !> Stresses at the Gauss points and extrapolated to the nodes.
   !!
   !! sigma = D B u at each Gauss point; in plane strain sig_zz = nu
   !! (sig_xx + sig_yy), in plane stress sig_zz = 0.  Nodal values come from
   !! a polynomial fitted to the Gauss-point values (least squares, exact
   !! interpolation when the number of points equals the number of terms):
   !! constant for one point; linear {1, s, t} for triangles with 3 or more
   !! points; on quadrilaterals with n x n points the tensor polynomial of
   !! degree p = min(n - 1, element order) in each variable, i.e. bilinear
   !! through 2x2 points and biquadratic Lagrange through 3x3 points (Q8, Q9),
   !! bilinear least squares for a Q4 with 3x3 or 4x4 points.  The fit is
   !! done per element, so nodal values are not averaged between elements.
   !!
   !! Ref: Hinton & Owen (1977), stress evaluation of the plane elasticity
   !!      program (sigma = D B u at the Gauss points); Hinton & Campbell,
   !!      IJNME 8 (1974) 461 (local least-squares smoothing); Zienkiewicz &
   !!      Taylor, vol. 1 (recovery from the Gauss points).
   pure subroutine element_stresses(ntype, nnode, elcod, young, poiss, ngaus, eldis, &
                                    ngp, xygp, sigma_gp, sigma_nd, ierr)
      integer, intent(in) :: ntype                  !! 1 plane stress, 2 plane
                                                    !! strain, 3 axisymmetric
      integer, intent(in) :: nnode                  !! nodes per element: 3, 4, 8 or 9
      real(dp), intent(in) :: elcod(2, nnode)       !! nodal coordinates [length]
      real(dp), intent(in) :: young                 !! Young's modulus [stress]
      real(dp), intent(in) :: poiss                 !! Poisson's ratio [-]
      integer, intent(in) :: ngaus                  !! Gauss rule, 0 = default
      real(dp), intent(in) :: eldis(2*nnode)        !! nodal displacements (u1,
                                                    !! v1, u2, ...) [length]
      integer, intent(out) :: ngp                   !! number of Gauss points
      real(dp), intent(out) :: xygp(2, max_gp)      !! global coordinates of the
                                                    !! Gauss points [length]
      real(dp), intent(out) :: sigma_gp(4, max_gp)  !! (xx, yy, xy, zz) at the Gauss points [stress]
      real(dp), intent(out) :: sigma_nd(4, nnode)   !! (xx, yy, xy, zz) extrapolated
                                                    !! to the nodes [stress]
      integer, intent(out) :: ierr                  !! status, see module header
      real(dp) :: posgp(2, max_gp), weigp(max_gp), dmatx(4, 4)
      real(dp) :: shape(nnode), cartd(2, nnode), bmatx(4, 2*nnode), dvolu
      real(dp) :: extra(nnode, max_gp)
      integer :: igaus

      xygp = 0.0_dp
      sigma_gp = 0.0_dp
      sigma_nd = 0.0_dp
      call prepare_rule(ntype, nnode, ngaus, posgp, weigp, ngp, ierr)
      if (ierr /= 0) then
         ngp = 0
         return
      end if
      call d_matrix(ntype, young, poiss, dmatx)
      do igaus = 1, ngp
         call gauss_point(ntype, nnode, elcod, posgp(:, igaus), weigp(igaus), 1.0_dp, &
                          shape, cartd, xygp(:, igaus), dvolu, igaus, ierr)
         if (ierr /= 0) then
            xygp = 0.0_dp
            sigma_gp = 0.0_dp
            return
         end if
         call b_matrix(ntype, nnode, shape, cartd, xygp(1, igaus), bmatx)
         sigma_gp(:, igaus) = matmul(dmatx, matmul(bmatx, eldis))
         if (ntype == 2) sigma_gp(4, igaus) = poiss*(sigma_gp(1, igaus) + sigma_gp(2, igaus))
      end do
      call extrapolation_matrix(nnode, ngp, posgp, extra)
      sigma_nd = matmul(sigma_gp(:, 1:ngp), transpose(extra(:, 1:ngp)))
   end subroutine element_stresses

   !> Internal force vector f = int B^T sigma dV of given nodal displacements.
   !!
   !! Equal to K u; assembled over the restrained nodes it gives the
   !! reactions.
   !!
   !! Ref: Owen & Hinton (1980), RESIDU (equivalent nodal forces of the
   !!      stresses); Zienkiewicz & Taylor, vol. 1 (nodal forces int B^T sigma dV).
   pure subroutine element_internal_force(ntype, nnode, elcod, young, poiss, thick, ngaus, &
                                          eldis, fint, ierr)
      integer, intent(in) :: ntype               !! 1 plane stress, 2 plane strain, 3 axisymmetric
      integer, intent(in) :: nnode               !! nodes per element: 3, 4, 8 or 9
      real(dp), intent(in) :: elcod(2, nnode)    !! nodal coordinates [length]
      real(dp), intent(in) :: young              !! Young's modulus [stress]
      real(dp), intent(in) :: poiss              !! Poisson's ratio [-]
      real(dp), intent(in) :: thick              !! thickness, plane problems [length]
      integer, intent(in) :: ngaus               !! Gauss rule, 0 = default
      real(dp), intent(in) :: eldis(2*nnode)     !! nodal displacements (u1, v1, ...) [length]
      real(dp), intent(out) :: fint(2*nnode)     !! nodal forces (fx1, fy1, ...) [force]
      integer, intent(out) :: ierr               !! status, see module header
      real(dp) :: posgp(2, max_gp), weigp(max_gp), dmatx(4, 4)
      real(dp) :: shape(nnode), cartd(2, nnode), bmatx(4, 2*nnode), sigma(4)
      real(dp) :: xy(2), dvolu
      integer :: ngp, igaus

      fint = 0.0_dp
      call prepare_rule(ntype, nnode, ngaus, posgp, weigp, ngp, ierr)
      if (ierr /= 0) return
      call d_matrix(ntype, young, poiss, dmatx)
      do igaus = 1, ngp
         call gauss_point(ntype, nnode, elcod, posgp(:, igaus), weigp(igaus), thick, &
                          shape, cartd, xy, dvolu, igaus, ierr)
         if (ierr /= 0) then
            fint = 0.0_dp
            return
         end if
         call b_matrix(ntype, nnode, shape, cartd, xy(1), bmatx)
         ! the 4th stress of plane strain does no work (eps_zz = 0): use D B u
         sigma = matmul(dmatx, matmul(bmatx, eldis))
         fint = fint + matmul(transpose(bmatx), sigma)*dvolu
      end do
   end subroutine element_internal_force

   !> Consistent nodal forces of a normal pressure and a tangential traction
   !! on one edge (LOADPS, distributed edge loads).
   !!
   !! Traction = -pn n + pt e, with n = (dy, -dx)/|.| the outward normal
   !! and e the unit tangent in the start -> end direction; pn and pt are
   !! interpolated from the edge nodes with the edge shape functions.
   !! The arc-length Jacobian |dx/ds| cancels against the normalisation of n
   !! and e, so the integrand is polynomial and a 5-point Gauss rule
   !! (`edge_ngaus`) integrates it exactly: quadratic edge, quadratic
   !! tractions and the 2 pi r weight make degree 7.
   !! Plane problems multiply by `thick`; axisymmetry by 2 pi r (total ring
   !! force).
   !!
   !! Ref: Owen & Hinton (1980), LOADPS; Zienkiewicz & Taylor, vol. 1
   !!      (consistent loads on element boundaries).
   pure subroutine edge_load(ntype, nn, edcod, pn, pt, thick, eforce)
      integer, intent(in) :: ntype             !! 1 plane stress, 2 plane strain, 3 axisymmetric
      integer, intent(in) :: nn                !! nodes on the edge: 2 or 3
      real(dp), intent(in) :: edcod(2, nn)     !! edge node coordinates, (start, end, mid) [length]
      real(dp), intent(in) :: pn(nn)           !! normal pressure at the edge
                                               !! nodes, + compressive [stress]
      real(dp), intent(in) :: pt(nn)           !! tangential traction at the edge
                                               !! nodes, + start->end [stress]
      real(dp), intent(in) :: thick            !! thickness, plane problems [length]
      real(dp), intent(out) :: eforce(2*nn)    !! nodal forces (fx1, fy1, ...) [force]
      real(dp) :: posgp(edge_ngaus), weigp(edge_ngaus)
      real(dp) :: shape(nn), deriv(nn), dxds, dyds, pgash, tgash, dvolu
      integer :: igaus, inode

      eforce = 0.0_dp
      call gauss_legendre(edge_ngaus, posgp, weigp)
      do igaus = 1, edge_ngaus
         call edge_shape(nn, posgp(igaus), shape, deriv)
         dxds = dot_product(deriv, edcod(1, :))
         dyds = dot_product(deriv, edcod(2, :))
         pgash = dot_product(shape, pn)
         tgash = dot_product(shape, pt)
         if (ntype == 3) then
            dvolu = weigp(igaus)*two_pi*dot_product(shape, edcod(1, :))
         else
            dvolu = weigp(igaus)*thick
         end if
         do inode = 1, nn
            eforce(2*inode - 1) = eforce(2*inode - 1) + &
                                  shape(inode)*(-pgash*dyds + tgash*dxds)*dvolu
            eforce(2*inode) = eforce(2*inode) + &
                              shape(inode)*(pgash*dxds + tgash*dyds)*dvolu
         end do
      end do
   end subroutine edge_load

   !> Consistent nodal forces of a uniform body force (LOADPS, gravity part).
   !!
   !! f_i = int N_i b dV with b = (bx, by) per unit volume.
   !!
   !! Ref: Owen & Hinton (1980), LOADPS; Zienkiewicz & Taylor, vol. 1
   !!      (consistent body-force loads int N^T b dV).
   pure subroutine body_load(ntype, nnode, elcod, thick, bx, by, ngaus, eforce, ierr)
      integer, intent(in) :: ntype               !! 1 plane stress, 2 plane strain, 3 axisymmetric
      integer, intent(in) :: nnode               !! nodes per element: 3, 4, 8 or 9
      real(dp), intent(in) :: elcod(2, nnode)    !! nodal coordinates [length]
      real(dp), intent(in) :: thick              !! thickness, plane problems [length]
      real(dp), intent(in) :: bx                 !! body force, x (r) component [force/volume]
      real(dp), intent(in) :: by                 !! body force, y (z) component [force/volume]
      integer, intent(in) :: ngaus               !! Gauss rule, 0 = default
      real(dp), intent(out) :: eforce(2*nnode)   !! nodal forces (fx1, fy1, ...) [force]
      integer, intent(out) :: ierr               !! status, see module header
      real(dp) :: posgp(2, max_gp), weigp(max_gp)
      real(dp) :: shape(nnode), cartd(2, nnode), xy(2), dvolu
      integer :: ngp, igaus

      eforce = 0.0_dp
      call prepare_rule(ntype, nnode, ngaus, posgp, weigp, ngp, ierr)
      if (ierr /= 0) return
      do igaus = 1, ngp
         call gauss_point(ntype, nnode, elcod, posgp(:, igaus), weigp(igaus), thick, &
                          shape, cartd, xy, dvolu, igaus, ierr)
         if (ierr /= 0) then
            eforce = 0.0_dp
            return
         end if
         eforce(1::2) = eforce(1::2) + shape*bx*dvolu
         eforce(2::2) = eforce(2::2) + shape*by*dvolu
      end do
   end subroutine body_load

   !> Smallest Jacobian determinant of an element: over all its nodes
   !! (corners and, for Q8/Q9, midside and centre nodes) and the points of
   !! the 3-point (triangle) or 3x3 (quadrilateral) Gauss rule.
   !!
   !! The raw determinant, without tolerance: negative for an inverted
   !! element, zero (to rounding) for a degenerate one.  For a parallelogram
   !! it equals area/4 (quadrilateral) or 2 x area (triangle), so a
   !! scale-free check compares it with the element's area.
   !!
   !! Ref: Hinton & Owen (1977), JACOB2; Zienkiewicz & Taylor, vol. 1
   !!      (conditions on the Jacobian of the isoparametric map).
   pure real(dp) function min_jacobian(nnode, elcod) result(djmin)
      integer, intent(in) :: nnode              !! nodes per element: 3, 4, 8 or 9
      real(dp), intent(in) :: elcod(2, nnode)   !! nodal coordinates [length]
      real(dp) :: posgp(2, max_gp), weigp(max_gp), snode(2, nnode)
      real(dp) :: shape(nnode), deriv(2, nnode)
      integer :: ngp, ipoin

      djmin = huge(1.0_dp)
      call node_natural_coords(nnode, snode)
      do ipoin = 1, nnode
         call shape_functions(nnode, snode(1, ipoin), snode(2, ipoin), shape, deriv)
         djmin = min(djmin, jacobian_determinant(nnode, elcod, deriv))
      end do
      call element_gauss_rule(nnode, 1, 3, posgp, weigp, ngp)
      do ipoin = 1, ngp
         call shape_functions(nnode, posgp(1, ipoin), posgp(2, ipoin), shape, deriv)
         djmin = min(djmin, jacobian_determinant(nnode, elcod, deriv))
      end do
   end function min_jacobian

   ! ------------------------------------------------------------------ helpers

   !> Check the element and analysis type and fetch the Gauss rule.
   pure subroutine prepare_rule(ntype, nnode, ngaus, posgp, weigp, ngp, ierr)
      integer, intent(in) :: ntype              !! analysis type
      integer, intent(in) :: nnode              !! nodes per element
      integer, intent(in) :: ngaus              !! requested rule, 0 = default
      real(dp), intent(out) :: posgp(2, max_gp) !! Gauss point natural coordinates
      real(dp), intent(out) :: weigp(max_gp)    !! Gauss weights
      integer, intent(out) :: ngp               !! number of points
      integer, intent(out) :: ierr              !! 0 or solid_bad_element

      ierr = 0
      call element_gauss_rule(nnode, ntype, ngaus, posgp, weigp, ngp)
      if (element_code(nnode) == 0 .or. ngp == 0) ierr = solid_bad_element
   end subroutine prepare_rule

   !> Shape functions, Cartesian derivatives, position and volume weight at
   !! one Gauss point.  Sets `ierr = igaus` for a non-positive Jacobian and
   !! `solid_bad_radius` for r <= 0 in axisymmetry.
   pure subroutine gauss_point(ntype, nnode, elcod, spos, weight, thick, shape, cartd, xy, &
                               dvolu, igaus, ierr)
      integer, intent(in) :: ntype              !! analysis type
      integer, intent(in) :: nnode              !! nodes per element
      real(dp), intent(in) :: elcod(2, nnode)   !! nodal coordinates [length]
      real(dp), intent(in) :: spos(2)           !! natural coordinates (s, t) of the point
      real(dp), intent(in) :: weight            !! Gauss weight
      real(dp), intent(in) :: thick             !! thickness, plane problems [length]
      real(dp), intent(out) :: shape(nnode)     !! shape functions
      real(dp), intent(out) :: cartd(2, nnode)  !! Cartesian derivatives [1/length]
      real(dp), intent(out) :: xy(2)            !! global coordinates of the point [length]
      real(dp), intent(out) :: dvolu            !! volume weight w det J (thick or 2 pi r) [volume]
      integer, intent(in) :: igaus              !! index of the point, reported on failure
      integer, intent(out) :: ierr              !! 0, igaus or solid_bad_radius
      real(dp) :: deriv(2, nnode), djacb
      logical :: ok

      ierr = 0
      dvolu = 0.0_dp
      call shape_functions(nnode, spos(1), spos(2), shape, deriv)
      xy = matmul(elcod, shape)
      call jacobian_2d(nnode, elcod, deriv, cartd, djacb, ok)
      if (.not. ok) then
         ierr = igaus
         return
      end if
      if (ntype == 3) then
         if (xy(1) <= 0.0_dp) then
            ierr = solid_bad_radius
            return
         end if
         dvolu = weight*djacb*two_pi*xy(1)
      else
         dvolu = weight*djacb*thick
      end if
   end subroutine gauss_point

   !> Matrix that maps Gauss-point values to nodal values by a local
   !! polynomial fit (see `element_stresses`).
   pure subroutine extrapolation_matrix(nnode, ngp, posgp, extra)
      integer, intent(in) :: nnode                 !! nodes per element
      integer, intent(in) :: ngp                   !! number of Gauss points
      real(dp), intent(in) :: posgp(2, max_gp)     !! natural coordinates of the points
      real(dp), intent(out) :: extra(nnode, max_gp) !! nodal value = sum_p extra(node, p) value(p)
      real(dp) :: snode(2, nnode), amat(ngp, 9), pnod(nnode, 9), anorm(9, 9), rhs(9, ngp)
      integer :: nterm, ipoin

      extra = 0.0_dp
      call node_natural_coords(nnode, snode)
      nterm = fit_terms(nnode, ngp)
      do ipoin = 1, ngp
         call fit_basis(nnode, nterm, posgp(:, ipoin), amat(ipoin, :))
      end do
      do ipoin = 1, nnode
         call fit_basis(nnode, nterm, snode(:, ipoin), pnod(ipoin, :))
      end do
      ! normal equations (A^T A) c = A^T v; at most 9 x 9 and well conditioned
      anorm(1:nterm, 1:nterm) = matmul(transpose(amat(:, 1:nterm)), amat(:, 1:nterm))
      rhs(1:nterm, :) = transpose(amat(:, 1:nterm))
      call solve_dense(nterm, ngp, anorm(1:nterm, 1:nterm), rhs(1:nterm, :))
      extra(:, 1:ngp) = matmul(pnod(:, 1:nterm), rhs(1:nterm, :))
   end subroutine extrapolation_matrix

   !> Number of terms of the extrapolation polynomial.
   pure integer function fit_terms(nnode, ngp) result(nterm)
      integer, intent(in) :: nnode   !! nodes per element
      integer, intent(in) :: ngp     !! number of Gauss points
      integer :: n, p

      if (ngp == 1) then
         nterm = 1
      else if (nnode == 3) then
         nterm = 3
      else
         n = nint(sqrt(real(ngp, dp)))
         p = min(n - 1, merge(1, 2, nnode == 4))
         nterm = (p + 1)**2
      end if
   end function fit_terms

   !> Values of the extrapolation basis at (s, t): 1; 1, s, t (triangle);
   !! 1, s, t, st (bilinear); or s^i t^j, 0 <= i, j <= 2 (biquadratic).
   pure subroutine fit_basis(nnode, nterm, spos, phi)
      integer, intent(in) :: nnode       !! nodes per element
      integer, intent(in) :: nterm       !! number of terms: 1, 3, 4 or 9
      real(dp), intent(in) :: spos(2)    !! (s, t)
      real(dp), intent(out) :: phi(9)    !! basis values; entries beyond nterm are zero
      real(dp) :: s, t

      s = spos(1)
      t = spos(2)
      phi = 0.0_dp
      phi(1) = 1.0_dp
      if (nterm == 1) return
      if (nnode == 3) then
         phi(2:3) = [s, t]
      else if (nterm == 4) then
         phi(2:4) = [s, t, s*t]
      else
         phi(2:9) = [s, t, s*t, s*s, t*t, s*s*t, s*t*t, s*s*t*t]
      end if
   end subroutine fit_basis

   !> Solve A X = B in place by Gaussian elimination with partial pivoting
   !! (small dense systems only; A is regular by construction here).
   pure subroutine solve_dense(n, nrhs, a, b)
      integer, intent(in) :: n              !! order of A
      integer, intent(in) :: nrhs           !! number of right-hand sides
      real(dp), intent(inout) :: a(n, n)    !! matrix, destroyed
      real(dp), intent(inout) :: b(n, nrhs) !! right-hand sides, replaced by the solution
      real(dp) :: rowa(n), rowb(nrhs), factor
      integer :: i, k, ipiv

      do k = 1, n
         ipiv = k - 1 + maxloc(abs(a(k:n, k)), dim=1)
         if (ipiv /= k) then
            rowa = a(k, :)
            a(k, :) = a(ipiv, :)
            a(ipiv, :) = rowa
            rowb = b(k, :)
            b(k, :) = b(ipiv, :)
            b(ipiv, :) = rowb
         end if
         do i = k + 1, n
            factor = a(i, k)/a(k, k)
            a(i, k:n) = a(i, k:n) - factor*a(k, k:n)
            b(i, :) = b(i, :) - factor*b(k, :)
         end do
      end do
      do k = n, 1, -1
         b(k, :) = (b(k, :) - matmul(a(k, k + 1:n), b(k + 1:n, :)))/a(k, k)
      end do
   end subroutine solve_dense

end module solid2d
