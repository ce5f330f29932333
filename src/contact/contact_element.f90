!> The zero-length contact spring (paper eqs. 3.31, 3.32), and its
!! generalisation to a node-to-segment or node-to-rigid-profile element.
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
!!
!! General element (node a against a point b of body B with u_b = sum_k w_k
!! u_k over the master nodes k = 2..nn, SPEC §1 kinematics unchanged): the
!! relative displacements are u_T = bt.v and u_n = bn.v with the dof vector
!! v = (u_a, u_2, ..., u_nn) and
!!     bt = ( t, -w_2 t, ..., -w_nn t),   bn = (-n, w_2 n, ..., w_nn n),
!! the stiffness is K_T bt bt^T + K_n bn bn^T and the internal forces
!! F_T bt + F_n bn.  For the two-node spring (nn = 2, w_2 = 1) the `pair_*`
!! routines call the `spring_*` ones, so node-to-node results are unchanged
!! to the last bit.
module contact_element
   use kinds, only: dp
   implicit none
   private
   public :: spring_stiffness, spring_kinematics, spring_forces
   public :: pair_stiffness, pair_kinematics, pair_forces

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

   !> Rows bt, bn of the relative-displacement operator of a general element.
   pure subroutine pair_operator(t, n, nn, w, bt, bn)
      real(dp), intent(in) :: t(2), n(2)
      integer, intent(in) :: nn              !! nodes of the element (slave + masters)
      real(dp), intent(in) :: w(:)           !! w(2:nn) weights of the master nodes
      real(dp), intent(out) :: bt(:), bn(:)  !! (2 nn)
      integer :: k
      bt(1:2) = t
      bn(1:2) = -n
      do k = 2, nn
         bt(2*k - 1:2*k) = -w(k)*t
         bn(2*k - 1:2*k) = w(k)*n
      end do
   end subroutine pair_operator

   pure logical function is_spring(nn, w)
      integer, intent(in) :: nn
      real(dp), intent(in) :: w(:)
      is_spring = nn == 2
      if (is_spring) is_spring = abs(w(2) - 1.0_dp) < epsilon(1.0_dp)
   end function is_spring

   !> Global (2 nn) x (2 nn) stiffness of an element: K_T bt bt^T + K_n bn bn^T.
   pure subroutine pair_stiffness(t, n, nn, w, kt, kn, ke)
      real(dp), intent(in) :: t(2), n(2)
      integer, intent(in) :: nn
      real(dp), intent(in) :: w(:)
      real(dp), intent(in) :: kt, kn
      real(dp), intent(out) :: ke(:, :)      !! at least (2 nn, 2 nn); the rest is zeroed
      real(dp) :: bt(2*nn), bn(2*nn)
      integer :: i, j
      ke = 0.0_dp
      if (is_spring(nn, w)) then
         call spring_stiffness(t, n, kt, kn, ke(1:4, 1:4))
         return
      end if
      call pair_operator(t, n, nn, w, bt, bn)
      do j = 1, 2*nn
         do i = 1, 2*nn
            ke(i, j) = kt*bt(i)*bt(j) + kn*bn(i)*bn(j)
         end do
      end do
   end subroutine pair_stiffness

   !> Relative displacements of an element from its dof values v = (u_a, u_2, ..., u_nn).
   pure subroutine pair_kinematics(t, n, nn, w, v, un, ut)
      real(dp), intent(in) :: t(2), n(2)
      integer, intent(in) :: nn
      real(dp), intent(in) :: w(:)
      real(dp), intent(in) :: v(:)           !! (2 nn) displacements (increments or totals)
      real(dp), intent(out) :: un            !! (u_b - u_a).n
      real(dp), intent(out) :: ut            !! (u_a - u_b).t
      real(dp) :: ub(2)
      integer :: k
      if (is_spring(nn, w)) then
         call spring_kinematics(t, n, v(1:2), v(3:4), un, ut)
         return
      end if
      ub = 0.0_dp
      do k = 2, nn
         ub = ub + w(k)*v(2*k - 1:2*k)
      end do
      call spring_kinematics(t, n, v(1:2), ub, un, ut)
   end subroutine pair_kinematics

   !> Internal-force vector (2 nn) of an element carrying F_n and F_T.
   pure subroutine pair_forces(t, n, nn, w, fn, ft, r)
      real(dp), intent(in) :: t(2), n(2)
      integer, intent(in) :: nn
      real(dp), intent(in) :: w(:)
      real(dp), intent(in) :: fn, ft
      real(dp), intent(out) :: r(:)          !! at least (2 nn); the rest is zeroed
      real(dp) :: ra(2)
      integer :: k
      r = 0.0_dp
      if (is_spring(nn, w)) then
         call spring_forces(t, n, fn, ft, r(1:4))
         return
      end if
      ra = ft*t - fn*n
      r(1:2) = ra
      do k = 2, nn
         r(2*k - 1:2*k) = -w(k)*ra
      end do
   end subroutine pair_forces
end module contact_element
