!> Readers of the CONTACT cards that say where an interface is (docs/deck-format.md):
!! SURFACE (a node set or node numbers on data cards), the data cards of PAIRS, MATCHING,
!! RIGID (FLAT, CIRCLE or POLYLINE with its vertex cards) and its reference node.  They
!! store what the cards say in the contact specification (model/contact_spec); the pairs
!! are built after reading (contact/contact_definition).
module deck_contact_geometry
   use kinds, only: dp
   use strings, only: itoa, rtoa, same_name
   use deck_lexer, only: deck_t, shown
   use model, only: node_set_t
   use contact_types, only: MATCH_NODE, MATCH_SEGMENT, rigid_body_t, RIGID_POLYLINE, RIGID_CIRCLE
   use contact_spec, only: contact_spec_t, iface_spec_t, pair_spec_t
   use deck_contact_fields, only: contact_cursor_t, check_tail, DATA_SURFACE, DATA_VERTICES
   implicit none
   private
   public :: read_surface, read_node_list, read_pair, read_matching, read_rigid, read_vertex

contains

   !> SURFACE: side A or B (11-20), then a set name (21-) or node numbers on
   !! the data cards that follow.
   subroutine read_surface(d, ic, s, cur)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(iface_spec_t), intent(inout) :: s
      type(contact_cursor_t), intent(inout) :: cur
      character(len=:), allocatable :: w
      logical :: ok
      integer :: iside
      ok = .true.
      call d%get_word(ic, 11, 20, 'CONTACT/SURFACE', 'SIDE', w, ok)
      iside = 0
      if (w == 'A') iside = 1
      if (w == 'B') iside = 2
      cur%iside = iside
      if (ok .and. iside == 0) then
         call d%error_at(ic, 11, 'E-CONTACT', &
            'CONTACT/SURFACE (columns 11-20) expected side A (upper body) or B (lower body), '// &
            'found "'//w//'"')
      else if (ok) then
         if (s%surf(iside)%given) then
            call d%error_at(ic, 1, 'E-CONTACT', 'CONTACT/SURFACE: surface '//w// &
               ' of this interface is given twice')
         end if
         s%surf(iside)%given = .true.
         s%surf(iside)%line = d%cards(ic)%line
         if (.not. allocated(s%surf(iside)%nodes)) allocate (s%surf(iside)%nodes(0))
         w = trim(adjustl(d%field_text(ic, 21, 100000)))
         if (len(w) > 0) then
            s%surf(iside)%set_name = w
         else
            cur%mode = DATA_SURFACE
         end if
      end if
   end subroutine read_surface

   !> A data card of a SURFACE: up to 16 node numbers, I5 each, appended to
   !! nodes(1:nn); first_line(node) is the line where a node was listed first.
   subroutine read_node_list(d, ic, npoin, nodes, nn, first_line)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic, npoin
      integer, intent(inout) :: nodes(:)         !! room for 16 more
      integer, intent(inout) :: nn
      integer, intent(inout) :: first_line(:)    !! (npoin)
      integer :: k, c1, node
      logical :: ok
      ok = .true.
      do k = 1, 16
         c1 = 1 + 5*(k - 1)
         if (len_trim(d%field_text(ic, c1, c1 + 4)) == 0) cycle
         call d%get_int(ic, c1, c1 + 4, 'CONTACT/SURFACE', 'NODE'//itoa(k), node, ok)
         if (.not. ok) return
         if (node < 1 .or. node > npoin) then
            call d%error_at(ic, c1, 'E-RANGE', 'CONTACT/SURFACE: node number (columns '// &
               itoa(c1)//'-'//itoa(c1 + 4)//') expected 1..'//itoa(npoin)//', found '//itoa(node))
            cycle
         end if
         if (first_line(node) /= 0) then
            call d%error_at(ic, c1, 'E-DUPLICATE', 'CONTACT/SURFACE: node '//itoa(node)// &
               ' (columns '//itoa(c1)//'-'//itoa(c1 + 4)//') is listed twice in this surface '// &
               '(first on line '//itoa(first_line(node))//')')
            cycle
         end if
         first_line(node) = d%cards(ic)%line
         nn = nn + 1
         nodes(nn) = node
      end do
      if (len_trim(d%field_text(ic, 81, 100000)) > 0) call d%error_at(ic, 81, 'E-EXTRA', &
         'CONTACT/SURFACE: at most 16 node numbers per card (columns 1-80)')
   end subroutine read_node_list

   !> A data card of PAIRS: NODEA, NODEB, G0, ALPHA (degrees), AREA.
   subroutine read_pair(d, ic, npoin, p, ok)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic, npoin
      type(pair_spec_t), intent(out) :: p     !! the pair (when ok)
      logical, intent(out) :: ok              !! the card holds a valid pair
      integer :: na, nb
      real(dp) :: g0, alpha, area
      ok = .true.
      call d%get_int(ic, 1, 5, 'CONTACT/PAIRS', 'NODEA', na, ok)
      call d%get_int(ic, 6, 10, 'CONTACT/PAIRS', 'NODEB', nb, ok)
      call d%get_real(ic, 11, 20, 'CONTACT/PAIRS', 'G0', g0, ok, default=0.0_dp)
      call d%get_real(ic, 21, 30, 'CONTACT/PAIRS', 'ALPHA', alpha, ok, default=0.0_dp)
      call d%get_real(ic, 31, 40, 'CONTACT/PAIRS', 'AREA', area, ok, default=0.0_dp)
      call check_tail(d, ic, 41, 'NODEA, NODEB, G0, ALPHA, AREA in columns 1-40', ok)
      if (.not. ok) return
      if (na < 1 .or. na > npoin .or. nb < 1 .or. nb > npoin) then
         call d%error_at(ic, 1, 'E-RANGE', &
            'CONTACT/PAIRS: node numbers (columns 1-10) expected 1..'//itoa(npoin)//', found '// &
            itoa(na)//' and '//itoa(nb))
         ok = .false.
         return
      end if
      if (len_trim(d%field_text(ic, 31, 40)) > 0 .and. .not. (area > 0.0_dp)) then
         call d%error_at(ic, 31, 'E-CONTACT', &
            'CONTACT/PAIRS: AREA (columns 31-40) expected a positive area, found '//rtoa(area))
         ok = .false.
         return
      end if
      p = pair_spec_t(node_a=na, node_b=nb, g0=g0, alpha=alpha, area=area, &
                      has_g0=len_trim(d%field_text(ic, 11, 20)) > 0, &
                      has_alpha=len_trim(d%field_text(ic, 21, 30)) > 0, &
                      has_area=len_trim(d%field_text(ic, 31, 40)) > 0, line=d%cards(ic)%line)
   end subroutine read_pair

   !> MATCHING: NODE (node-to-node pairs) or SEGMENT (nodes of A against edges of B).
   subroutine read_matching(d, ic, s)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(iface_spec_t), intent(inout) :: s
      character(len=:), allocatable :: w
      logical :: ok
      ok = .true.
      call d%get_word(ic, 11, 20, 'CONTACT/MATCHING', 'MATCHING', w, ok)
      call check_tail(d, ic, 21, 'NODE or SEGMENT in columns 11-20', ok)
      if (.not. ok) return
      if (w == 'NODE') then
         s%law%matching = MATCH_NODE
      else if (w == 'SEGMENT') then
         s%law%matching = MATCH_SEGMENT
      else
                  call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/MATCHING (columns 11-20) '// &
            'expected NODE (node-to-node pairs) or SEGMENT (nodes of A against edges of B), '// &
            'found "'//w//'"')
      end if
            if (s%have_matching) call d%error_at(ic, 1, 'E-CONTACT', 'CONTACT/MATCHING: given '// &
         'twice for this interface')
      s%have_matching = .true.
      s%matching_line = d%cards(ic)%line
   end subroutine read_matching

   !> RIGID: SHAPE (11-20), NREF (21-30), then FLAT X1 Y1 X2 Y2 or CIRCLE XC
   !! YC R (31-70) [model length]; POLYLINE takes its vertices from data cards.
   !! The body becomes side B of the current interface.  NREF may instead be
   !! the name of a node set of one node (a MESH block's NODE card).
   subroutine read_rigid(d, ic, npoin, sets, cs, cur)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic, npoin
      type(node_set_t), allocatable, intent(in) :: sets(:)
      type(contact_spec_t), intent(inout) :: cs
      type(contact_cursor_t), intent(inout) :: cur
      character(len=:), allocatable :: shape
      integer :: nref, nif
      real(dp) :: x(4)
      integer :: k
      character(len=2), parameter :: fnames(4) = ['X1', 'Y1', 'X2', 'Y2'], cnames(3) = ['XC', &
         'YC', 'R ']
      logical :: ok
      type(rigid_body_t) :: rb
      ok = .true.
      nif = cur%nif
      if (cs%ifaces(nif)%law%rigid > 0) then
         call d%error_at(ic, 1, 'E-RIGID', &
            'CONTACT/RIGID: this interface already has a rigid body (one RIGID card per '// &
            'interface; start another INTERFACE)')
         return
      end if
      call d%get_word(ic, 11, 20, 'CONTACT/RIGID', 'SHAPE', shape, ok)
      call reference_node(d, ic, sets, nref, ok)
      if (.not. ok) return
      if (nref < 1 .or. nref > npoin) then
         call d%error_at(ic, 21, 'E-RANGE', &
            'CONTACT/RIGID: NREF (columns 21-30) expected the reference node 1..'//itoa(npoin)// &
            ', found '//itoa(nref))
         return
      end if
      rb%node = nref
      rb%line = d%cards(ic)%line
      select case (shape)
      case ('FLAT')
         call d%get_real(ic, 31, 40, 'CONTACT/RIGID', 'X1', x(1), ok)
         call d%get_real(ic, 41, 50, 'CONTACT/RIGID', 'Y1', x(2), ok)
         call d%get_real(ic, 51, 60, 'CONTACT/RIGID', 'X2', x(3), ok)
         call d%get_real(ic, 61, 70, 'CONTACT/RIGID', 'Y2', x(4), ok)
         call check_tail(d, ic, 71, 'FLAT, NREF, X1, Y1, X2, Y2 in columns 11-70', ok)
         do k = 1, 4
            call d%check_coordinate(ic, 21 + 10*k, 'CONTACT/RIGID', trim(fnames(k)), x(k), ok)
         end do
         if (.not. ok) return
         rb%shape = RIGID_POLYLINE
         rb%xy = reshape(x, [2, 2])
      case ('CIRCLE')
         call d%get_real(ic, 31, 40, 'CONTACT/RIGID', 'XC', x(1), ok)
         call d%get_real(ic, 41, 50, 'CONTACT/RIGID', 'YC', x(2), ok)
         call d%get_real(ic, 51, 60, 'CONTACT/RIGID', 'R', x(3), ok)
         call check_tail(d, ic, 61, 'CIRCLE, NREF, XC, YC, R in columns 11-60', ok)
         do k = 1, 3
            call d%check_coordinate(ic, 21 + 10*k, 'CONTACT/RIGID', trim(cnames(k)), x(k), ok)
         end do
         if (.not. ok) return
         if (.not. (x(3) > 0.0_dp)) then
            call d%error_at(ic, 51, 'E-RIGID', &
               'CONTACT/RIGID: R (columns 51-60) expected a positive radius, found '//rtoa(x(3)))
            return
         end if
         rb%shape = RIGID_CIRCLE
         rb%centre = x(1:2)
         rb%radius = x(3)
         allocate (rb%xy(2, 0))
      case ('POLYLINE')
         call check_tail(d, ic, 31, &
            'POLYLINE and NREF in columns 11-30 (the vertices follow on data cards)', ok)
         if (.not. ok) return
         rb%shape = RIGID_POLYLINE
         allocate (rb%xy(2, 0))
         cur%mode = DATA_VERTICES
      case default
         call d%error_at(ic, 11, 'E-RIGID', &
            'CONTACT/RIGID: SHAPE (columns 11-20) expected FLAT, CIRCLE or POLYLINE, found "'// &
            shape//'"')
         return
      end select
      cs%rigids = [cs%rigids, rb]
      cs%ifaces(nif)%law%rigid = size(cs%rigids)
   end subroutine read_rigid

   !> RIGID's NREF (columns 21-30): a node number, or the name of a node set
   !! of exactly one node (the extra node of a MESH block's NODE card).
   subroutine reference_node(d, ic, sets, nref, ok)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(node_set_t), allocatable, intent(in) :: sets(:)
      integer, intent(out) :: nref
      logical, intent(inout) :: ok
      character(len=:), allocatable :: f
      integer :: k
      nref = 0
      f = trim(adjustl(d%field_text(ic, 21, 30)))
      if (len(f) == 0 .or. verify(f(1:1), &
         'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ_') /= 0) then
         call d%get_int(ic, 21, 30, 'CONTACT/RIGID', 'NREF', nref, ok)
         return
      end if
      if (allocated(sets)) then
         do k = 1, size(sets)
            if (.not. same_name(sets(k)%name, f)) cycle
            if (size(sets(k)%nodes) /= 1) then
               call d%error_at(ic, 21, 'E-RIGID', &
                  'CONTACT/RIGID: NREF (columns 21-30) names the set "'//f//'" of '// &
                  itoa(size(sets(k)%nodes))//' nodes; expected one node (a NODE card of the '// &
                  'MESH block)')
               ok = .false.
               return
            end if
            nref = sets(k)%nodes(1)
            return
         end do
      end if
      call d%error_at(ic, 21, 'E-RIGID', &
         'CONTACT/RIGID: NREF (columns 21-30) expected a node number or the name of an extra '// &
         'node (MESH block, NODE card), found "'//shown(f)//'"')
      ok = .false.
   end subroutine reference_node

   !> A vertex of a POLYLINE profile: X (1-10), Y (11-20) [model length].
   subroutine read_vertex(d, ic, xy, ok)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      real(dp), intent(out) :: xy(2)          !! the vertex (when ok)
      logical, intent(out) :: ok              !! the card holds a valid vertex
      ok = .true.
      call d%get_real(ic, 1, 10, 'CONTACT/RIGID', 'X', xy(1), ok)
      call d%get_real(ic, 11, 20, 'CONTACT/RIGID', 'Y', xy(2), ok)
      call d%check_coordinate(ic, 1, 'CONTACT/RIGID', 'X', xy(1), ok)
      call d%check_coordinate(ic, 11, 'CONTACT/RIGID', 'Y', xy(2), ok)
      call check_tail(d, ic, 21, 'X, Y of a vertex in columns 1-20', ok)
   end subroutine read_vertex
end module deck_contact_geometry
