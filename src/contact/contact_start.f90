!> The start of a contact analysis: initial states of the pairs and the start
!! pressure p_m of eq. (4.1), from which the first increment's secant
!! stiffnesses come (eqs. 4.5, 4.6).
module contact_start
   use kinds, only: dp
   use errors, only: status_t, STAT_INPUT
   use model, only: model_t, NTYPE_AXISYMMETRIC
   use contact_types, only: LAW_ROUGH, LAW_IDEAL, UPDATE_RETURN, PAIR_RIGID
   use contact_algorithm, only: contact_state_t, contact_init
   use contact_laws, only: normal_pressure
   use restraint_check, only: find_bodies
   implicit none
   private
   public :: init_contact_states, start_pressure, increment_pressure, separating_load

contains

   !> Initial states of the pairs: closed when their gap is within the gap
   !! tolerance (CONTACT ... GAPTOL, or 1e-9 of the model's size).
   subroutine init_contact_states(m, st)
      type(model_t), intent(in) :: m
      type(contact_state_t), intent(out) :: st
      real(dp) :: gap_tol
      gap_tol = m%contact%opts%gap_tol
      if (gap_tol < 0.0_dp) gap_tol = 1.0e-9_dp*model_size(m)
      call contact_init(m%contact, gap_tol, st)
      if (m%contact%opts%n_start == 0) call support_free_rigids(m, gap_tol, st)
   end subroutine init_contact_states

   !> A rigid body whose reference node is free in some direction and none of
   !! whose pairs starts closed (a ball on a half-space touching it on the axis,
   !! where the pair has no area, every other pair with a gap) would be held by
   !! nothing in the first solution: its active pairs of the smallest gap (to
   !! gap_tol) start closed, as START NSTART would close them.  The increment's
   !! Newton iteration closes or opens them on their law.
   subroutine support_free_rigids(m, gap_tol, st)
      type(model_t), intent(in) :: m
      real(dp), intent(in) :: gap_tol
      type(contact_state_t), intent(inout) :: st
      integer :: ir, j, k
      logical :: fixed(2), mine(size(m%contact%pairs))
      real(dp) :: gmin
      if (.not. allocated(m%contact%rigids)) return
      do ir = 1, size(m%contact%rigids)
         fixed = .false.
         do k = 1, size(m%fixes)
            if (m%fixes(k)%node /= m%contact%rigids(ir)%node) cycle
            fixed = fixed .or. m%fixes(k)%fixed
         end do
         ! in axisymmetry the body moves axially only
         if (fixed(2) .and. (fixed(1) .or. m%ntype == NTYPE_AXISYMMETRIC)) cycle
         mine = [(m%contact%pairs(j)%kind == PAIR_RIGID .and. &
                  m%contact%ifaces(m%contact%pairs(j)%iface)%rigid == ir .and. &
                  (m%contact%pairs(j)%area > 0.0_dp .or. &
                   m%contact%ifaces(m%contact%pairs(j)%iface)%law == LAW_IDEAL), &
                  j=1, size(m%contact%pairs))]
         if (.not. any(mine) .or. any(mine .and. st%s%closed)) cycle
         gmin = minval(m%contact%pairs%g0, mask=mine)
         where (mine .and. m%contact%pairs%g0 <= gmin + gap_tol) st%s%closed = .true.
      end do
   end subroutine support_free_rigids

   !> Largest extent of the mesh in x or y.
   pure real(dp) function model_size(m)
      type(model_t), intent(in) :: m
      model_size = max(maxval(m%coord(1, :)) - minval(m%coord(1, :)), &
                       maxval(m%coord(2, :)) - minval(m%coord(2, :)))
   end function model_size

   !> Start pressure p_m of eq. (4.1) for the rough interfaces: the resultant
   !! of the first load increment on body A, projected on the mean contact
   !! normal, over the nominal area of the initially closed pairs; or START PM.
   !! When body A carries no load (e.g. a foundation under a loaded punch, or a
   !! half-space under a rigid body driven through its reference node) the
   !! resultant on the bodies of side B is taken instead: both balance the
   !! same contact force.
   subroutine start_pressure(m, fcase, dlam1, st, status)
      type(model_t), intent(in) :: m
      real(dp), intent(in) :: fcase(:, :, :)   !! (2, npoin, ncase) forces of
                                               !! the load cases at factor 1
      real(dp), intent(in) :: dlam1(:)         !! (ncase) load factors of the first increment
      type(contact_state_t), intent(inout) :: st
      type(status_t), intent(inout) :: status
      integer, allocatable :: body(:), nolinks(:, :)
      logical, allocatable :: in_a(:), in_b(:)
      real(dp) :: nbar(2), aa, fn, pfit
      integer :: nbody, j
      logical :: any_closed

      st%p_start = m%contact%opts%p_start
      if (st%p_start > 0.0_dp) return
      allocate (body(m%npoin), nolinks(2, 0), in_a(m%npoin), in_b(m%npoin))
      call find_bodies(m, nolinks, body, nbody)
      call pair_bodies(m, body, nbody, &
                       [(m%contact%ifaces(m%contact%pairs(j)%iface)%law == LAW_ROUGH, &
                                         j=1, size(m%contact%pairs))], in_a, in_b)
      nbar = 0.0_dp
      aa = 0.0_dp
      any_closed = .false.
      do j = 1, size(m%contact%pairs)
         associate (pr => m%contact%pairs(j))
            if (m%contact%ifaces(pr%iface)%law /= LAW_ROUGH) cycle
            if (.not. st%s(j)%closed) cycle
            any_closed = .true.
            aa = aa + pr%area
            nbar = nbar + pr%area*pr%n
         end associate
      end do
      if (.not. any_closed) then
         st%p_start = 0.0_dp
         return
      end if
      nbar = nbar/max(norm2(nbar), tiny(1.0_dp))
      fn = normal_part(resultant(in_a))
      if (.not. (fn > 0.0_dp)) fn = normal_part(resultant(in_b .and. .not. in_a))
      if (.not. (fn > 0.0_dp)) fn = preload()
      pfit = fit_pressure()
      if (.not. (fn > 0.0_dp .or. pfit > 0.0_dp) .or. .not. (aa > 0.0_dp)) then
         call status%set(STAT_INPUT, &
                         'contact: the first increment applies no force normal to the contact '// &
                         'surface on either body and no bolt preload (it is displacement-'// &
                         'driven), so the start pressure p_m of eq. (4.1) '// &
                         'cannot be computed; give it on a CONTACT START card (PM)')
         return
      end if
      st%p_start = fn/aa + pfit
   contains
      !> |f . nbar|, or 0 where that is round-off of f, a force along the surface (a push along
      !! a shrink fit's axis: its radial part over the bore's area was a start pressure of
      !! 1e-16 and a tangential stiffness that let the hub run away).
      real(dp) function normal_part(f)
         real(dp), intent(in) :: f(2)
         normal_part = abs(dot_product(f, nbar))
         if (normal_part <= 1.0e-9_dp*norm2(f)) normal_part = 0.0_dp
      end function normal_part

      !> The pressure an interference fit brings: the closed rough pairs that start
      !! penetrated (g0 < 0) pressed by the whole overlap on their virgin law, p(-g0), averaged
      !! over the closed pairs' area -- the bodies' own compliance takes part of the overlap, so
      !! this is the upper end of the pressure the first increment reaches (0: no overlap).
      real(dp) function fit_pressure()
         integer :: k
         fit_pressure = 0.0_dp
         do k = 1, size(m%contact%pairs)
            associate (pr => m%contact%pairs(k))
               if (m%contact%ifaces(pr%iface)%law /= LAW_ROUGH) cycle
               if (.not. st%s(k)%closed .or. .not. (pr%g0 < 0.0_dp)) cycle
               associate (ifc => m%contact%ifaces(pr%iface))
                  fit_pressure = fit_pressure + pr%area*normal_pressure(-pr%g0, ifc%cn, ifc%m, &
                                                                          ifc%cn2, ifc%m2, &
                                                                          .false., 0.0_dp, 0.0_dp)
               end associate
            end associate
         end do
         fit_pressure = fit_pressure/aa
      end function fit_pressure

      !> The clamping force of the bolts preloaded in the first increment (a joint whose
      !! first stage is the preload alone): the sections' forces F dlambda, each along its
      !! axis, projected on the mean normal.  The section's force acts on its reference
      !! node, which belongs to no body, and the clamped parts carry it through the
      !! interfaces of the grip (docs/bolts.md).
      real(dp) function preload()
         real(dp) :: f(2)
         integer :: k
         preload = 0.0_dp
         if (.not. allocated(m%pretensions)) return
         do k = 1, size(m%pretensions)
            associate (p => m%pretensions(k))
               if (p%icase < 1 .or. p%icase > size(dlam1)) cycle
               f = 0.0_dp
               f(p%axis) = p%force*dlam1(p%icase)
               preload = preload + abs(dot_product(f, nbar))
            end associate
         end do
      end function preload

      !> Resultant of the first load increment on the flagged nodes.
      function resultant(flag) result(f)
         logical, intent(in) :: flag(:)
         real(dp) :: f(2), df(2)
         integer :: ip, ic
         f = 0.0_dp
         do ip = 1, m%npoin
            if (.not. flag(ip)) cycle
            do ic = 1, size(dlam1)
               df = dlam1(ic)*fcase(:, ip, ic)
               f = f + df
            end do
         end do
      end function resultant
   end subroutine start_pressure

   !> The pressure a load increment is expected to bring to the rough pairs
   !! resting at their zero-force end after an unloading (`st%p_incr`, used by
   !! begin_increment for a reload from zero): the increment's resultant on
   !! body A pressing it onto B, normal to the mean contact normal, over the
   !! area of the rough pairs that are closed or on their unloading branch --
   !! the start pressure of eq. (4.1) for the increment at hand.  Zero when no
   !! pair rests at its zero-force end, when the increment pulls the bodies
   !! apart or holds the load, or is driven by prescribed displacements only
   !! (no force to measure it by), and with the paper's EXPLICIT scheme.
   !! Ref: Altenbach & Buczkowski, eq. (4.1); SPEC §4.1.
   subroutine increment_pressure(m, fcase, dlam, st)
      type(model_t), intent(in) :: m
      real(dp), intent(in) :: fcase(:, :, :)   !! (2, npoin, ncase) forces of
                                               !! the load cases at factor 1
      real(dp), intent(in) :: dlam(:)          !! (ncase) load factor increments of the increment
      type(contact_state_t), intent(inout) :: st
      integer, allocatable :: body(:), nolinks(:, :)
      logical, allocatable :: in_a(:), in_b(:), rough(:)
      real(dp) :: nbar(2), aa, fa, fb, p
      integer :: nbody, j, i
      logical :: resting, opposed

      st%p_incr = 0.0_dp
      if (m%contact%opts%update /= UPDATE_RETURN) return
      resting = .false.
      do j = 1, size(m%contact%pairs)
         associate (pr => m%contact%pairs(j), s => st%s(j))
            if (m%contact%ifaces(pr%iface)%law /= LAW_ROUGH .or. pr%area <= 0.0_dp) cycle
            if (.not. s%on_unloading) cycle
            if (.not. s%closed .or. s%fn <= 1.0e-9_dp*pr%area*s%pa) resting = .true.
         end associate
      end do
      if (.not. resting) return
      allocate (body(m%npoin), nolinks(2, 0), in_a(m%npoin), in_b(m%npoin))
      call find_bodies(m, nolinks, body, nbody)
      rough = [(m%contact%ifaces(m%contact%pairs(j)%iface)%law == LAW_ROUGH .and. &
                m%contact%pairs(j)%area > 0.0_dp, j=1, size(m%contact%pairs))]
      call pressure_through(rough, st%p_incr, opposed)
      ! interfaces of opposed normals (a stack: a gasket between two flanges, the load
      ! passing through each interface in turn): their mean normal vanishes, so each
      ! interface on its own, the largest pressure of them
      if (opposed) then
         st%p_incr = 0.0_dp
         do i = 1, size(m%contact%ifaces)
            call pressure_through(rough .and. m%contact%pairs%iface == i, p, opposed)
            st%p_incr = max(st%p_incr, p)
         end do
      end if
   contains
      !> The pressure of the increment's load through the pairs flagged in `use`, and
      !! whether their normals are opposed (|sum A n| below half the sum of A).
      subroutine pressure_through(use, pr_incr, opp)
         logical, intent(in) :: use(:)
         real(dp), intent(out) :: pr_incr
         logical, intent(out) :: opp
         pr_incr = 0.0_dp
         opp = .false.
         call pair_bodies(m, body, nbody, use, in_a, in_b)
         nbar = 0.0_dp
         aa = 0.0_dp
         do j = 1, size(m%contact%pairs)
            associate (pr => m%contact%pairs(j))
               if (.not. use(j)) cycle
               if (.not. (st%s(j)%closed .or. st%s(j)%on_unloading)) cycle
               aa = aa + pr%area
               nbar = nbar + pr%area*pr%n
            end associate
         end do
         if (.not. (aa > 0.0_dp)) return
         opp = norm2(nbar) < 0.5_dp*aa
         nbar = nbar/max(norm2(nbar), tiny(1.0_dp))
         ! n points from B into A: a load pressing A onto B points along -n on A, +n on B
         fa = -dot_product(increment_resultant(in_a), nbar)
         fb = dot_product(increment_resultant(in_b .and. .not. in_a), nbar)
         if (abs(fa) > 0.0_dp) then
            pr_incr = max(fa, 0.0_dp)/aa
         else
            pr_incr = max(fb, 0.0_dp)/aa
         end if
         if (.not. (pr_incr < huge(1.0_dp))) pr_incr = 0.0_dp
      end subroutine pressure_through

      !> Resultant of the increment's loads on the flagged nodes.
      function increment_resultant(flag) result(f)
         logical, intent(in) :: flag(:)
         real(dp) :: f(2)
         integer :: ip, ic
         f = 0.0_dp
         do ip = 1, m%npoin
            if (.not. flag(ip)) cycle
            do ic = 1, size(dlam)
               f = f + dlam(ic)*fcase(:, ip, ic)
            end do
         end do
      end function increment_resultant
   end subroutine increment_pressure

   !> The load that pulls the bodies of the contact apart: the resultant of the
   !! nodal forces f on the bodies of side A (those holding the pairs' nodes
   !! A), projected on the mean contact normal of all pairs (from B into A), in
   !! the direction away from B; when side A carries no load, the resultant on
   !! the bodies of side B, away from A.  Negative: the load presses them
   !! together; 0 without pairs.  For the diagnosis of a singular system whose
   !! pairs are all open (a load that pulls a body off the only support it has).
   real(dp) function separating_load(m, f) result(fsep)
      type(model_t), intent(in) :: m
      real(dp), intent(in) :: f(:, :)           !! (2, npoin) nodal forces
      integer, allocatable :: body(:), nolinks(:, :)
      logical, allocatable :: in_a(:), in_b(:), use(:)
      real(dp) :: nbar(2), fa(2), fb(2)
      integer :: nbody, j
      fsep = 0.0_dp
      if (size(m%contact%pairs) == 0) return
      use = m%contact%pairs%area > 0.0_dp
      if (.not. any(use)) return
      nbar = 0.0_dp
      do j = 1, size(m%contact%pairs)
         if (use(j)) nbar = nbar + m%contact%pairs(j)%area*m%contact%pairs(j)%n
      end do
      nbar = nbar/max(norm2(nbar), tiny(1.0_dp))
      allocate (body(m%npoin), nolinks(2, 0), in_a(m%npoin), in_b(m%npoin))
      call find_bodies(m, nolinks, body, nbody)
      call pair_bodies(m, body, nbody, use, in_a, in_b)
      fa = [sum(f(1, :), mask=in_a), sum(f(2, :), mask=in_a)]
      fb = [sum(f(1, :), mask=in_b .and. .not. in_a), sum(f(2, :), mask=in_b .and. .not. in_a)]
      ! n points from B into A: a load pulling A off B points along +n on A, -n on B
      if (abs(dot_product(fa, nbar)) > 0.0_dp) then
         fsep = dot_product(fa, nbar)
      else
         fsep = -dot_product(fb, nbar)
      end if
   end function separating_load

   !> The nodes of the bodies that hold side A (in_a) and side B (in_b) of
   !! the pairs flagged in `use` (a rigid body's reference node, body 0: in_b
   !! itself), in one pass over the pairs and one over the nodes.
   subroutine pair_bodies(m, body, nbody, use, in_a, in_b)
      type(model_t), intent(in) :: m
      integer, intent(in) :: body(:)           !! (npoin) body of each node (find_bodies), 0: none
      integer, intent(in) :: nbody
      logical, intent(in) :: use(:)            !! (npair) the pairs that count
      logical, intent(out) :: in_a(:), in_b(:) !! (npoin)
      logical :: fa(0:nbody), fb(0:nbody)
      integer :: j, k, ip
      fa = .false.
      fb = .false.
      in_b = .false.
      do j = 1, size(m%contact%pairs)
         if (.not. use(j)) cycle
         associate (pr => m%contact%pairs(j))
            if (body(pr%node_a) > 0) fa(body(pr%node_a)) = .true.
            do k = 2, pr%nn
               if (body(pr%nodes(k)) > 0) then
                  fb(body(pr%nodes(k))) = .true.
               else
                  in_b(pr%nodes(k)) = .true.      ! a rigid body's reference node
               end if
            end do
         end associate
      end do
      do ip = 1, size(body)
         in_a(ip) = body(ip) > 0 .and. fa(max(body(ip), 0))
         in_b(ip) = in_b(ip) .or. (body(ip) > 0 .and. fb(max(body(ip), 0)))
      end do
   end subroutine pair_bodies
end module contact_start
