!> Isoparametric mapping and strain–displacement matrix of the 2-D solids.
!!
!! Strain vector (4 components): (eps_xx, eps_yy, gamma_xy, eps_zz), where
!! the 4th component is the hoop strain eps_theta = u_r/r in axisymmetry
!! (x = r radial, y = z axial) and is identically zero for plane problems.
!! Dof order: (u1, v1, u2, v2, ...).
!!
!! Ref: Hinton & Owen, *Finite Element Programming* (1977), routines JACOB2
!!      and BMATPS; Zienkiewicz & Taylor, *The Finite Element Method*,
!!      vol. 1 (plane and axisymmetric elasticity; isoparametric mapping).
module kinematics_2d
   use kinds, only: dp
   implicit none
   private

   public :: jacobian_2d, jacobian_determinant, b_matrix, jacobian_rel_tol

   !> A Jacobian determinant below `jacobian_rel_tol * |J|_F**2` counts as
   !! non-positive: it is zero to rounding and must not be divided by.
   real(dp), parameter :: jacobian_rel_tol = 1.0e-12_dp

contains

   !> Determinant of the Jacobian of the map (s, t) -> (x, y).
   !!
   !! No tolerance is applied; this is the raw value used by element
   !! quality checks.
   pure real(dp) function jacobian_determinant(nnode, elcod, deriv) result(djacb)
      integer, intent(in) :: nnode             !! nodes per element
      real(dp), intent(in) :: elcod(2, nnode)  !! nodal coordinates (x, y) [length]
      real(dp), intent(in) :: deriv(2, nnode)  !! dN/ds, dN/dt at the point
      real(dp) :: xjacm(2, 2)

      xjacm = matmul(deriv, transpose(elcod))
      djacb = xjacm(1, 1)*xjacm(2, 2) - xjacm(1, 2)*xjacm(2, 1)
   end function jacobian_determinant

   !> Jacobian, its determinant and the Cartesian shape-function derivatives
   !! at one point (JACOB2).
   !!
   !! `xjacm(i, j) = d x_j / d s_i`.  If the determinant is not positive
   !! (below `jacobian_rel_tol * |J|_F**2`, which includes exact zero and
   !! rounding noise around it) the element is inverted or degenerate at
   !! this point: `ok` is false, `cartd` is zero and nothing is divided.
   !!
   !! Ref: Hinton & Owen (1977), JACOB2; Zienkiewicz & Taylor, vol. 1
   !!      (isoparametric mapping, transformation of derivatives).
   pure subroutine jacobian_2d(nnode, elcod, deriv, cartd, djacb, ok)
      integer, intent(in) :: nnode              !! nodes per element
      real(dp), intent(in) :: elcod(2, nnode)   !! nodal coordinates (x, y) [length]
      real(dp), intent(in) :: deriv(2, nnode)   !! dN/ds, dN/dt at the point
      real(dp), intent(out) :: cartd(2, nnode)  !! dN/dx (row 1), dN/dy (row 2) [1/length]
      real(dp), intent(out) :: djacb            !! det J [area per unit natural area]
      logical, intent(out) :: ok                !! false if det J is not positive
      real(dp) :: xjacm(2, 2), xjaci(2, 2)

      xjacm = matmul(deriv, transpose(elcod))
      djacb = xjacm(1, 1)*xjacm(2, 2) - xjacm(1, 2)*xjacm(2, 1)
      ok = djacb > jacobian_rel_tol*sum(xjacm**2)
      if (.not. ok) then
         cartd = 0.0_dp
         return
      end if
      xjaci(1, 1) = xjacm(2, 2)/djacb
      xjaci(2, 2) = xjacm(1, 1)/djacb
      xjaci(1, 2) = -xjacm(1, 2)/djacb
      xjaci(2, 1) = -xjacm(2, 1)/djacb
      cartd = matmul(xjaci, deriv)
   end subroutine jacobian_2d

   !> Strain–displacement matrix (BMATPS with the hoop row).
   !!
   !! Rows: eps_x = du/dx, eps_y = dv/dy, gamma_xy = du/dy + dv/dx and,
   !! for `ntype = 3`, eps_theta = u/r.  On the axis (`radius <= 0`) u/r is
   !! replaced by its limit du/dr, which holds because u_r = 0 there; the
   !! element routines never evaluate B on the axis (all Gauss points are
   !! interior), so this branch only guards against a division by zero.
   !!
   !! Ref: Hinton & Owen (1977), BMATPS; Zienkiewicz & Taylor, vol. 1
   !!      (axisymmetric strain matrix with the hoop row u/r).
   pure subroutine b_matrix(ntype, nnode, shape, cartd, radius, bmatx)
      integer, intent(in) :: ntype                 !! 1 plane stress, 2 plane strain, 3 axisymmetric
      integer, intent(in) :: nnode                 !! nodes per element
      real(dp), intent(in) :: shape(nnode)         !! shape functions at the point
      real(dp), intent(in) :: cartd(2, nnode)      !! Cartesian derivatives at the point
      real(dp), intent(in) :: radius               !! r at the point (used only
                                                   !! for ntype 3) [length]
      real(dp), intent(out) :: bmatx(4, 2*nnode)   !! B matrix [1/length]
      integer :: inode, mgash, ngash

      bmatx = 0.0_dp
      do inode = 1, nnode
         mgash = 2*inode - 1
         ngash = 2*inode
         bmatx(1, mgash) = cartd(1, inode)
         bmatx(2, ngash) = cartd(2, inode)
         bmatx(3, mgash) = cartd(2, inode)
         bmatx(3, ngash) = cartd(1, inode)
         if (ntype == 3) then
            if (radius > 0.0_dp) then
               bmatx(4, mgash) = shape(inode)/radius
            else
               bmatx(4, mgash) = cartd(1, inode)
            end if
         end if
      end do
   end subroutine b_matrix

end module kinematics_2d
