!> Gauss quadrature rules for the 2-D solid elements and their edges.
!!
!! One-dimensional Gauss–Legendre rules (1 to 5 points) on [-1, 1], their
!! tensor products on the quadrilateral [-1, 1]², and symmetric rules on the
!! triangle with corners (0,0), (1,0), (0,1).  Triangle weights sum to 1/2,
!! the area of that triangle, so that for every element
!! \( \int_{\Omega_e} f \, d\Omega \approx \sum_p f(s_p, t_p)\, \det J(s_p, t_p)\, w_p \).
!!
!! Quadrilateral points are numbered with s running fastest:
!! point \( p = i + (j-1) n \) sits at \( (s_i, t_j) \).  The 1-D points are in
!! ascending order.
!!
!! Defaults (`ngaus = 0`): T3 one point for plane problems and three points
!! for axisymmetry (the hoop strain u/r varies over the element); Q4 2x2;
!! Q8 and Q9 3x3.  See `docs/elements.md` for the reasoning.
!!
!! Ref: Hinton & Owen, *Finite Element Programming* (1977), routine GAUSSQ;
!!      Zienkiewicz & Taylor, *The Finite Element Method*, vol. 1
!!      (numerical integration: Gauss–Legendre and triangle rules);
!!      Strang & Fix (1973) for the 6-point and Radon (1948) for the
!!      7-point triangle rule.
module quadrature
   use kinds, only: dp
   implicit none
   private

   public :: max_gp, max_gp_1d, gauss_legendre, element_gauss_rule, default_ngaus, &
             valid_ngaus

   integer, parameter :: max_gp_1d = 5   !! most points of a 1-D rule
   integer, parameter :: max_gp = 16     !! most points of an element rule (4x4 on a quad)

contains

   !> One-dimensional Gauss–Legendre rule on [-1, 1] (GAUSSQ).
   !!
   !! The rule with `ngaus` points integrates polynomials of degree
   !! `2*ngaus - 1` exactly.  Abscissae and weights are the closed forms,
   !! so they are correct to the last bit of `dp`.  For `ngaus` outside
   !! 1..5 every entry is set to zero (the weights then do not sum to 2).
   !!
   !! Ref: Hinton & Owen (1977), GAUSSQ; Zienkiewicz & Taylor, vol. 1
   !!      (table of Gauss–Legendre abscissae and weights).
   pure subroutine gauss_legendre(ngaus, posgp, weigp)
      integer, intent(in) :: ngaus         !! number of points, 1..5
      real(dp), intent(out) :: posgp(:)    !! abscissae, ascending; size >= ngaus
      real(dp), intent(out) :: weigp(:)    !! weights; size >= ngaus
      real(dp) :: a, b

      posgp = 0.0_dp
      weigp = 0.0_dp
      select case (ngaus)
      case (1)
         posgp(1) = 0.0_dp
         weigp(1) = 2.0_dp
      case (2)
         a = 1.0_dp/sqrt(3.0_dp)
         posgp(1:2) = [-a, a]
         weigp(1:2) = [1.0_dp, 1.0_dp]
      case (3)
         a = sqrt(0.6_dp)
         posgp(1:3) = [-a, 0.0_dp, a]
         weigp(1:3) = [5.0_dp, 8.0_dp, 5.0_dp]/9.0_dp
      case (4)
         a = sqrt(3.0_dp/7.0_dp - 2.0_dp/7.0_dp*sqrt(1.2_dp))
         b = sqrt(3.0_dp/7.0_dp + 2.0_dp/7.0_dp*sqrt(1.2_dp))
         posgp(1:4) = [-b, -a, a, b]
         weigp(2) = (18.0_dp + sqrt(30.0_dp))/36.0_dp
         weigp(1) = (18.0_dp - sqrt(30.0_dp))/36.0_dp
         weigp(3) = weigp(2)
         weigp(4) = weigp(1)
      case (5)
         a = sqrt(5.0_dp - 2.0_dp*sqrt(10.0_dp/7.0_dp))/3.0_dp
         b = sqrt(5.0_dp + 2.0_dp*sqrt(10.0_dp/7.0_dp))/3.0_dp
         posgp(1:5) = [-b, -a, 0.0_dp, a, b]
         weigp(3) = 128.0_dp/225.0_dp
         weigp(2) = (322.0_dp + 13.0_dp*sqrt(70.0_dp))/900.0_dp
         weigp(1) = (322.0_dp - 13.0_dp*sqrt(70.0_dp))/900.0_dp
         weigp(4) = weigp(2)
         weigp(5) = weigp(1)
      end select
   end subroutine gauss_legendre

   !> Default number of Gauss points for an element (per direction for
   !! quadrilaterals, total for triangles); 0 for an unsupported element.
   !!
   !! Ref: Hinton & Owen (1977), NGAUS of GAUSSQ/STIFFP; Zienkiewicz &
   !!      Taylor, vol. 1 (minimum and optimal integration order).
   pure integer function default_ngaus(nnode, ntype) result(ngaus)
      integer, intent(in) :: nnode   !! nodes per element: 3, 4, 8 or 9
      integer, intent(in) :: ntype   !! 1 plane stress, 2 plane strain, 3 axisymmetric

      ngaus = 0
      if (ntype < 1 .or. ntype > 3) return
      select case (nnode)
      case (3)
         ! the plane T3 has constant strain; the axisymmetric one has u/r
         if (ntype == 3) then
            ngaus = 3
         else
            ngaus = 1
         end if
      case (4)
         ngaus = 2
      case (8, 9)
         ngaus = 3
      end select
   end function default_ngaus

   !> True if `ngaus` (0 = default) names a rule that `element_gauss_rule`
   !! provides for this element and analysis type.
   pure logical function valid_ngaus(nnode, ntype, ngaus)
      integer, intent(in) :: nnode   !! nodes per element: 3, 4, 8 or 9
      integer, intent(in) :: ntype   !! 1 plane stress, 2 plane strain, 3 axisymmetric
      integer, intent(in) :: ngaus   !! 0 (default) or the requested rule

      valid_ngaus = .false.
      if (default_ngaus(nnode, ntype) == 0) return
      select case (nnode)
      case (3)
         valid_ngaus = any(ngaus == [0, 1, 3, 6, 7])
      case (4, 8, 9)
         valid_ngaus = ngaus >= 0 .and. ngaus <= 4
      end select
   end function valid_ngaus

   !> Two-dimensional Gauss rule of an element (GAUSSQ, extended to triangles).
   !!
   !! Quadrilaterals: `ngaus` x `ngaus` tensor-product Gauss–Legendre points,
   !! `ngaus` = 1..4 (degree 2*ngaus-1 in each variable).
   !! Triangles: `ngaus` = 1 (centroid, degree 1), 3 (interior points
   !! (1/6,1/6), (2/3,1/6), (1/6,2/3), degree 2), 6 (degree 4) or 7 (degree 5).
   !! The 4-point degree-3 rule is deliberately absent: its negative weight
   !! can make a stiffness matrix indefinite.  All triangle points are strictly
   !! inside the element, so r > 0 at every point of an axisymmetric element.
   !! An invalid combination returns `ngp = 0`.
   !!
   !! Ref: Hinton & Owen (1977), GAUSSQ; Zienkiewicz & Taylor, vol. 1
   !!      (quadrilateral and triangle rules); Strang & Fix (1973); Radon (1948).
   pure subroutine element_gauss_rule(nnode, ntype, ngaus, posgp, weigp, ngp)
      integer, intent(in) :: nnode             !! nodes per element: 3, 4, 8 or 9
      integer, intent(in) :: ntype             !! 1 plane stress, 2 plane strain, 3 axisymmetric
      integer, intent(in) :: ngaus             !! 0 = default, else see above
      real(dp), intent(out) :: posgp(2, max_gp) !! natural coordinates (s, t) of the points
      real(dp), intent(out) :: weigp(max_gp)    !! weights (sum 4 on quads, 1/2 on triangles)
      integer, intent(out) :: ngp              !! number of points; 0 if the request is invalid
      real(dp) :: x1(max_gp_1d), w1(max_gp_1d)
      integer :: n, i, j

      posgp = 0.0_dp
      weigp = 0.0_dp
      ngp = 0
      if (.not. valid_ngaus(nnode, ntype, ngaus)) return
      n = ngaus
      if (n == 0) n = default_ngaus(nnode, ntype)

      if (nnode == 3) then
         call triangle_rule(n, posgp, weigp)
         ngp = n
      else
         call gauss_legendre(n, x1, w1)
         do j = 1, n
            do i = 1, n
               posgp(1, i + (j - 1)*n) = x1(i)
               posgp(2, i + (j - 1)*n) = x1(j)
               weigp(i + (j - 1)*n) = w1(i)*w1(j)
            end do
         end do
         ngp = n*n
      end if
   end subroutine element_gauss_rule

   !> Symmetric rules on the unit right triangle, weights summing to 1/2.
   !! Points are given in area coordinates (L1, L2, L3) with s = L2, t = L3.
   pure subroutine triangle_rule(npt, posgp, weigp)
      integer, intent(in) :: npt                 !! 1, 3, 6 or 7
      real(dp), intent(inout) :: posgp(2, max_gp) !! (s, t) of the points
      real(dp), intent(inout) :: weigp(max_gp)    !! weights
      real(dp) :: a, b, wa, wb
      ! Strang & Fix 6-point rule, degree 4 (weights for unit area)
      real(dp), parameter :: a6 = 0.445948490915964886318329253883_dp
      real(dp), parameter :: b6 = 0.091576213509770743459571463402_dp
      real(dp), parameter :: wa6 = 0.223381589678011465944640007799_dp
      real(dp), parameter :: wb6 = 0.109951743655321867388693325535_dp

      select case (npt)
      case (1)
         posgp(:, 1) = [1.0_dp, 1.0_dp]/3.0_dp
         weigp(1) = 0.5_dp
      case (3)
         a = 1.0_dp/6.0_dp
         posgp(:, 1) = [a, a]
         posgp(:, 2) = [4.0_dp*a, a]
         posgp(:, 3) = [a, 4.0_dp*a]
         weigp(1:3) = 0.5_dp/3.0_dp
      case (6)
         call orbit3(a6, 0.5_dp*wa6, posgp(:, 1:3), weigp(1:3))
         call orbit3(b6, 0.5_dp*wb6, posgp(:, 4:6), weigp(4:6))
      case (7)
         a = (6.0_dp - sqrt(15.0_dp))/21.0_dp
         b = (6.0_dp + sqrt(15.0_dp))/21.0_dp
         wa = (155.0_dp - sqrt(15.0_dp))/1200.0_dp
         wb = (155.0_dp + sqrt(15.0_dp))/1200.0_dp
         posgp(:, 1) = [1.0_dp, 1.0_dp]/3.0_dp
         weigp(1) = 0.5_dp*9.0_dp/40.0_dp
         call orbit3(a, 0.5_dp*wa, posgp(:, 2:4), weigp(2:4))
         call orbit3(b, 0.5_dp*wb, posgp(:, 5:7), weigp(5:7))
      end select
   end subroutine triangle_rule

   !> The three points with area coordinates (1-2a, a, a) and permutations.
   pure subroutine orbit3(a, w, pos, wgt)
      real(dp), intent(in) :: a       !! repeated area coordinate
      real(dp), intent(in) :: w       !! weight of each point
      real(dp), intent(out) :: pos(2, 3)
      real(dp), intent(out) :: wgt(3)

      pos(:, 1) = [a, a]
      pos(:, 2) = [1.0_dp - 2.0_dp*a, a]
      pos(:, 3) = [a, 1.0_dp - 2.0_dp*a]
      wgt = w
   end subroutine orbit3

end module quadrature
