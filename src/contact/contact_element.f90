!> The zero-length two-node contact spring (paper eqs. 3.31, 3.32).
!!
!! Local dofs (t_a, n_a, t_b, n_b); spring stiffnesses K_T = A_j k_T and
!! K_n = A_j k_n (N/mm: the area is applied once, SPEC D6).  In global dofs
!! (u_ax, u_ay, u_bx, u_by) the matrix Theta^T K_L Theta is
!!     [ K  -K ]      K = K_T t t^T + K_n n n^T
!!     [-K   K ]
!! Relative kinematics (SPEC §1): closure u_n = (u_b - u_a).n - g0, tangential
!! displacement u_T = (u_a - u_b).t.  Forces: F_n >= 0 compressive pushes A
!! along +n; the tangential force F_T acts on A as -F_T t.  The spring's
!! internal-force vector (the d(energy)/du that balances the external loads) is
!!     r_a = F_T t - F_n n,   r_b = -r_a.
module contact_element
   use kinds, only: dp
   implicit none
   private
   public :: spring_stiffness, spring_kinematics, spring_forces

contains

   !> Global 4x4 stiffness of a spring, eq. (3.31): Theta^T [K_c]_L Theta.
   pure subroutine spring_stiffness(t, n, kt, kn, ke)
      real(dp), intent(in) :: t(2), n(2)   !! unit tangent and normal of body B
      real(dp), intent(in) :: kt, kn       !! spring stiffnesses K_T, K_n [force/length]
      real(dp), intent(out) :: ke(4, 4)
      real(dp) :: k(2, 2)
      integer :: i, j
      do j = 1, 2
         do i = 1, 2
            k(i, j) = kt*t(i)*t(j) + kn*n(i)*n(j)
         end do
      end do
      ke(1:2, 1:2) = k
      ke(3:4, 3:4) = k
      ke(1:2, 3:4) = -k
      ke(3:4, 1:2) = -k
   end subroutine spring_stiffness

   !> Normal and tangential relative displacements of a pair (increments or totals; no gap).
   pure subroutine spring_kinematics(t, n, ua, ub, un, ut)
      real(dp), intent(in) :: t(2), n(2), ua(2), ub(2)
      real(dp), intent(out) :: un   !! (u_b - u_a).n, positive when A approaches B
      real(dp), intent(out) :: ut   !! (u_a - u_b).t, A relative to B
      un = dot_product(ub - ua, n)
      ut = dot_product(ua - ub, t)
   end subroutine spring_kinematics

   !> Internal-force vector of a spring carrying F_n and F_T: (r_a, r_b).
   pure subroutine spring_forces(t, n, fn, ft, r)
      real(dp), intent(in) :: t(2), n(2), fn, ft
      real(dp), intent(out) :: r(4)
      r(1:2) = ft*t - fn*n
      r(3:4) = -r(1:2)
   end subroutine spring_forces
end module contact_element
