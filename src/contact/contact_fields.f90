!> The contact quantities of a step as output fields: per pair the contact
!! stresses p = F/A (zero-area pairs extrapolated from their neighbours), the
!! forces, closures, slips, friction and stiffnesses of the committed states,
!! the state codes NS_* / TS_* of the contact fields record, and the mode
!! changes of every pair in the step (chatter shows as a pair reaching the
!! cap of the contact algorithm).
!!
!! Filled once per accepted step from the committed states; read as they are
!! by the result file and the listing, which know nothing of the contact
!! algorithm.  Also the pairs' spacing, which the driver's small-sliding
!! check compares the slip with.
module contact_fields
   use kinds, only: dp
   use contact_types, only: contact_def_t, contact_pair_t, rigid_body_t, PAIR_RIGID, RIGID_CIRCLE
   use records, only: contact_fields_t, NS_OPEN, NS_LOADING, NS_UNLOADING
   use contact_algorithm, only: contact_state_t
   implicit none
   private
   public :: build_contact_fields, extrapolate_zero_area, pair_spacing

contains

   !> The contact fields record of the committed states `st`.
   subroutine build_contact_fields(cdef, st, cf)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(in) :: st
      type(contact_fields_t), intent(inout) :: cf
      integer :: j, np
      np = size(cdef%pairs)
      call allocate_fields(cf, np)
      associate (area => cdef%pairs%area)
         where (area > 0.0_dp)
            cf%pressure = st%s%fn/area
            cf%shear = st%s%ft/area
         else where
            cf%pressure = 0.0_dp
            cf%shear = 0.0_dp
         end where
      end associate
      call extrapolate_zero_area(cdef%pairs, cf%pressure)
      call extrapolate_zero_area(cdef%pairs, cf%shear)
      do j = 1, np
         if (.not. st%s(j)%closed) then
            cf%normal_state(j) = NS_OPEN
         else if (st%s(j)%on_unloading) then
            cf%normal_state(j) = NS_UNLOADING
         else
            cf%normal_state(j) = NS_LOADING
         end if
         cf%tangential_state(j) = st%s(j)%tstate
      end do
      cf%force_normal = st%s%fn
      cf%force_tangential = st%s%ft
      cf%closure = st%s%un
      cf%slip = st%s%ut
      cf%slip_irreversible = st%s%utp
      cf%slip_gross = st%s%utp_gross
      cf%effective_slip = st%s%ve
      cf%friction = st%s%mu
      cf%stiffness_normal = st%s%kn
      cf%stiffness_tangential = st%s%kt
      cf%switches = st%md%nswitch
   end subroutine build_contact_fields

   !> Every field of the record with np entries (kept when already so).
   subroutine allocate_fields(cf, np)
      type(contact_fields_t), intent(inout) :: cf
      integer, intent(in) :: np
      if (allocated(cf%pressure)) then
         if (size(cf%pressure) == np) return
         cf = contact_fields_t()
      end if
      allocate (cf%pressure(np), cf%shear(np), cf%force_normal(np), cf%force_tangential(np), &
                cf%closure(np), &
                cf%slip(np), cf%slip_irreversible(np), cf%slip_gross(np), cf%effective_slip(np), &
                cf%friction(np), &
                cf%normal_state(np), cf%tangential_state(np), cf%stiffness_normal(np), &
                cf%stiffness_tangential(np), &
                cf%switches(np))
   end subroutine allocate_fields

   !> Pairs of zero area (a quadratic axisymmetric edge on the axis) carry no
   !! spring; report their stress by linear extrapolation from the two
   !! nearest pairs of the same interface (SPEC §3.2 caveat).
   pure subroutine extrapolate_zero_area(pairs, v)
      type(contact_pair_t), intent(in) :: pairs(:)
      real(dp), intent(inout) :: v(:)          !! (npair) a per-pair stress
      integer :: j, k, k1, k2
      real(dp) :: d, d1, d2
      do j = 1, size(v)
         if (pairs(j)%area > 0.0_dp) cycle
         k1 = 0
         k2 = 0
         d1 = huge(1.0_dp)
         d2 = huge(1.0_dp)
         do k = 1, size(v)
            if (k == j .or. pairs(k)%area <= 0.0_dp) cycle
            if (pairs(k)%iface /= pairs(j)%iface) cycle
            d = norm2(pairs(k)%position - pairs(j)%position)
            if (d < d1) then
               k2 = k1
               d2 = d1
               k1 = k
               d1 = d
            else if (d < d2) then
               k2 = k
               d2 = d
            end if
         end do
         if (k1 > 0 .and. k2 > 0 .and. d2 > d1) then
            v(j) = v(k1) + (v(k1) - v(k2))*d1/(d2 - d1)
         else if (k1 > 0) then
            v(j) = v(k1)
         end if
      end do
   end subroutine extrapolate_zero_area

   !> Distance from every pair to the nearest other pair (huge for a lone
   !! pair): node-to-node contact assumes slips well below it.  Given the
   !! contact definition, a pair with a rigid profile takes the profile's own
   !! scale instead, since its partner is the profile, not the next pair: the
   !! radius of a circle (a slip s turns the pair's fixed normal by s/R), the
   !! shortest segment of a polyline (a slip across a vertex or off a flat's end).
   pure function pair_spacing(pairs, cdef) result(spacing)
      type(contact_pair_t), intent(in) :: pairs(:)
      type(contact_def_t), intent(in), optional :: cdef  !! its interfaces and rigid bodies
      real(dp) :: spacing(size(pairs))
      integer :: j, k, ir
      spacing = huge(1.0_dp)
      do j = 1, size(pairs)
         if (present(cdef) .and. pairs(j)%kind == PAIR_RIGID) then
            ir = cdef%ifaces(pairs(j)%iface)%rigid
            if (ir > 0) then
               spacing(j) = profile_scale(cdef%rigids(ir))
               cycle
            end if
         end if
         do k = 1, size(pairs)
            if (k == j) cycle
            spacing(j) = min(spacing(j), norm2(pairs(k)%position - pairs(j)%position))
         end do
      end do
   end function pair_spacing

   !> The length over which a rigid profile's normal stays put: a circle's
   !! radius, a polyline's shortest segment.
   pure real(dp) function profile_scale(rb) result(h)
      type(rigid_body_t), intent(in) :: rb
      integer :: k
      if (rb%shape == RIGID_CIRCLE) then
         h = rb%radius
         return
      end if
      h = huge(1.0_dp)
      do k = 1, size(rb%xy, 2) - 1
         h = min(h, norm2(rb%xy(:, k + 1) - rb%xy(:, k)))
      end do
   end function profile_scale
end module contact_fields
