!> GROUP cards: restraints and loads applied to a named set of nodes or
!! edges (a gmsh physical curve or point; see docs/deck-format.md).
!!
!! A GROUP card is the usual card of its block with the first field(s)
!! (the node, or the element and its edge nodes) replaced by the word GROUP
!! in columns 1-10 and the set's name in columns 11-30:
!!
!!     RESTRAINTS   GROUP     <name 11-30> CODE 31-35  UX 36-45  UY 46-55  CASE 56-60
!!     LOADS/POINT  GROUP     <name 11-30> FX 31-40    FY 41-50  CASE 51-55
!!     LOADS/EDGE   GROUP     <name 11-30> PN 31-40    PT 41-50  CASE 51-55
!!
!! A restraint or point load applies to every node of the set; an edge load
!! (uniform normal pressure PN, positive compressive, and tangential traction
!! PT, positive along the boundary with the body on the left, i.e.
!! anticlockwise around the body) to every edge of the set.
module group_cards
   use kinds, only: dp
   use strings, only: itoa, rtoa
   use deck_lexer, only: deck_t, shown
   use model, only: model_t, MAX_CASE, restraint_t, point_load_t, edge_load_t, find_node_set, &
         find_edge_set
   use topology, only: element_edge_nodes
   implicit none
   private
   public :: is_group_card, read_group_restraint, read_group_point_load, read_group_edge_load, &
             check_restraint_overlaps

contains

   !> A card whose first word is GROUP.
   logical function is_group_card(d, ic)
      type(deck_t), intent(in) :: d
      integer, intent(in) :: ic
      is_group_card = .false.
      if (.not. d%is_keyword_card(ic)) return
      is_group_card = d%keyword(ic) == 'GROUP'
   end function is_group_card

   !> The set name of a GROUP card (columns 11-30); '' after reporting an error.
   function group_name(d, ic, card) result(name)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      character(len=*), intent(in) :: card
      character(len=:), allocatable :: name
      if (trim(adjustl(d%field_text(ic, 1, 10))) /= 'GROUP' .and. &
          trim(adjustl(d%field_text(ic, 1, 10))) /= 'group' .and. &
          trim(adjustl(d%field_text(ic, 1, 10))) /= 'Group') then
         call d%error_at(ic, 1, 'E-CARD', &
                         card//': expected the word GROUP in columns 1-10, found "'// &
                         trim(d%field_text(ic, 1, 10))//'"')
         name = ''
         return
      end if
      name = trim(adjustl(d%field_text(ic, 11, 30)))
      if (len(name) == 0) call d%error_at(ic, 11, 'E-MISSING', &
                                          card//': GROUP expected a set name in '// &
                                          'columns 11-30, found a blank field')
   end function group_name

   !> Names of the node or edge sets, for messages.
   function set_names(m, edges) result(s)
      type(model_t), intent(in) :: m
      logical, intent(in) :: edges
      character(len=:), allocatable :: s
      integer :: k
      s = ''
      if (edges) then
         if (allocated(m%edge_sets)) then
            do k = 1, size(m%edge_sets)
               if (len(s) > 0) s = s//', '
               s = s//'"'//m%edge_sets(k)%name//'"'
            end do
         end if
      else
         if (allocated(m%node_sets)) then
            do k = 1, size(m%node_sets)
               if (len(s) > 0) s = s//', '
               s = s//'"'//m%node_sets(k)%name//'"'
            end do
         end if
      end if
      if (len(s) == 0) then
         s = 'none (named sets come from the physical curves and points of a MESH block)'
      end if
   end function set_names

   subroutine check_tail(d, ic, col, card, expected, ok)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic, col
      character(len=*), intent(in) :: card, expected
      logical, intent(inout) :: ok
      character(len=:), allocatable :: tail
      tail = trim(adjustl(d%field_text(ic, col, 100000)))
      if (len(tail) > 0) then
         call d%error_at(ic, col, 'E-EXTRA', card//': expected '//expected//', found more: "'// &
                         shown(tail)//'"')
         ok = .false.
      end if
   end subroutine check_tail

   !> RESTRAINTS GROUP card: one restraint entry per node of the set, appended to list(1:n).
   subroutine read_group_restraint(d, ic, m, list, n)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(model_t), intent(in) :: m
      type(restraint_t), allocatable, intent(inout) :: list(:)
      integer, intent(inout) :: n
      character(len=:), allocatable :: name
      integer :: code, icase, ks, k
      real(dp) :: ux, uy
      logical :: ok
      character(len=*), parameter :: card = 'RESTRAINTS'

      name = group_name(d, ic, card)
      if (len(name) == 0) return
      ok = .true.
      call d%get_int(ic, 31, 35, card, 'CODE', code, ok)
      call d%get_real(ic, 36, 45, card, 'UX', ux, ok, default=0.0_dp)
      call d%get_real(ic, 46, 55, card, 'UY', uy, ok, default=0.0_dp)
      call d%get_int(ic, 56, 60, card, 'CASE', icase, ok, default=1)
      call check_tail(d, ic, 61, card, 'GROUP, NAME, CODE, UX, UY, CASE in columns 1-60', ok)
      call d%check_magnitude(ic, 36, card, 'UX', ux, ok)
      call d%check_magnitude(ic, 46, card, 'UY', uy, ok)
      if (.not. ok) return
      ks = find_node_set(m, name)
      if (ks == 0) then
         call d%error_at(ic, 11, 'E-GROUP', card//': GROUP "'//name// &
                         '" is no node set of the mesh; known: '// &
                         set_names(m, .false.))
         return
      end if
      if (all(code /= [1, 10, 11])) then
         call d%error_at(ic, 31, 'E-CODE', &
                         card//': CODE (columns 31-35) expected 10 (x fixed), '// &
                         '01 (y fixed) or 11 (both), found '//itoa(code))
         return
      end if
      if (icase < 1 .or. icase > MAX_CASE) then
         call d%error_at(ic, 56, 'E-RANGE', card//': CASE (columns 56-60) expected a load case '// &
                         '1..'//itoa(MAX_CASE)//', found '// &
                         itoa(icase))
         return
      end if
      if (code < 10 .and. abs(ux) > 0.0_dp) then
         call d%error_at(ic, 36, 'E-CODE', card//': UX = '//rtoa(ux)// &
                         ' is prescribed but CODE '//itoa(code)// &
                         ' leaves x free')
         return
      end if
      if (mod(code, 10) == 0 .and. abs(uy) > 0.0_dp) then
         call d%error_at(ic, 46, 'E-CODE', card//': UY = '//rtoa(uy)// &
                         ' is prescribed but CODE '//itoa(code)// &
                         ' leaves y free')
         return
      end if
      associate (nodes => m%node_sets(ks)%nodes)
         do k = 1, size(nodes)
            if (n >= size(list)) list = [list, list]
            n = n + 1
            list(n) = restraint_t(node=nodes(k), fixed=[code >= 10, mod(code, 10) == 1], &
                                  value=[ux, uy], &
                                  icase=icase, line=d%cards(ic)%line)
         end do
      end associate
   end subroutine read_group_restraint

   !> Nodes restrained by several cards (GROUP cards overlap at corners): allowed
   !! when no direction is prescribed twice with different values or cases.
   subroutine check_restraint_overlaps(d, m, list)
      type(deck_t), intent(inout) :: d
      type(model_t), intent(in) :: m
      type(restraint_t), intent(in) :: list(:)
      integer, allocatable :: first(:, :)
      integer :: k, dof, j
      allocate (first(2, max(m%npoin, 1)))
      first = 0
      do k = 1, size(list)
         if (list(k)%node < 1 .or. list(k)%node > m%npoin) cycle
         do dof = 1, 2
            if (.not. list(k)%fixed(dof)) cycle
            j = first(dof, list(k)%node)
            if (j == 0) then
               first(dof, list(k)%node) = k
            else if (abs(list(j)%value(dof) - list(k)%value(dof)) > 0.0_dp .or. list(j)%icase /= &
                     list(k)%icase) then
               call d%errors%add('E-DUPLICATE', 'RESTRAINTS: node '//itoa(list(k)%node)// &
                                 ' gets two different '// &
                                 'prescribed '//merge('x', 'y', dof == 1)// &
                                 ' displacements (lines '// &
                                 itoa(list(j)%line)//' and '//itoa(list(k)%line)//')', &
                                 file=d%file, &
                                 line=list(k)%line)
            end if
         end do
      end do
   end subroutine check_restraint_overlaps

   !> LOADS/POINT GROUP card: the force on every node of the set.
   subroutine read_group_point_load(d, ic, m, pl, npl)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(model_t), intent(in) :: m
      type(point_load_t), allocatable, intent(inout) :: pl(:)
      integer, intent(inout) :: npl
      integer :: icase, ks, k
      real(dp) :: f(2)

      call read_group_load_fields(d, ic, m, 'LOADS/POINT', ['FX', 'FY'], .false., f, icase, ks)
      if (ks == 0) return
      associate (nodes => m%node_sets(ks)%nodes)
         do k = 1, size(nodes)
            if (npl >= size(pl)) pl = [pl, pl]
            npl = npl + 1
            pl(npl) = point_load_t(node=nodes(k), force=f, icase=icase, line=d%cards(ic)%line)
         end do
      end associate
   end subroutine read_group_point_load

   !> LOADS/EDGE GROUP card: uniform pressure and traction on every edge of the set.
   subroutine read_group_edge_load(d, ic, m, el, nel)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(model_t), intent(in) :: m
      type(edge_load_t), allocatable, intent(inout) :: el(:)
      integer, intent(inout) :: nel
      integer :: icase, ks, k, loc(3), nloc, ie
      real(dp) :: p(2)

      call read_group_load_fields(d, ic, m, 'LOADS/EDGE', ['PN', 'PT'], .true., p, icase, ks)
      if (ks == 0) return
      associate (s => m%edge_sets(ks))
         do k = 1, size(s%ielem)
            ie = s%ielem(k)
            call element_edge_nodes(m%nnode_e(ie), s%iedge(k), loc, nloc)
            if (nel >= size(el)) el = [el, el]
            nel = nel + 1
            el(nel) = edge_load_t()
            el(nel)%ielem = ie
            el(nel)%nn = nloc
            el(nel)%nodes(1:nloc) = m%lnods(loc(1:nloc), ie)
            el(nel)%pn(1:nloc) = p(1)
            el(nel)%pt(1:nloc) = p(2)
            el(nel)%icase = icase
            el(nel)%line = d%cards(ic)%line
         end do
      end associate
   end subroutine read_group_edge_load

   !> The fields the LOADS GROUP cards share: the set's name, two values
   !! (columns 31-40 and 41-50, default 0), CASE (51-55, default 1) and nothing
   !! beyond; the set must exist (a node set, or with edges an edge set) and
   !! CASE be >= 1.  ks: the set's index, 0 when the card is in error
   !! (reported).
   subroutine read_group_load_fields(d, ic, m, card, names, edges, v, icase, ks)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(model_t), intent(in) :: m
      character(len=*), intent(in) :: card, names(2)
      logical, intent(in) :: edges
      real(dp), intent(out) :: v(2)
      integer, intent(out) :: icase, ks
      character(len=:), allocatable :: name
      logical :: ok

      ks = 0
      v = 0.0_dp
      icase = 1
      name = group_name(d, ic, card)
      if (len(name) == 0) return
      ok = .true.
      call d%get_real(ic, 31, 40, card, names(1), v(1), ok, default=0.0_dp)
      call d%get_real(ic, 41, 50, card, names(2), v(2), ok, default=0.0_dp)
      call d%get_int(ic, 51, 55, card, 'CASE', icase, ok, default=1)
      call check_tail(d, ic, 56, card, 'GROUP, NAME, '//names(1)//', '//names(2)// &
                      ', CASE in columns 1-55', ok)
      call d%check_magnitude(ic, 31, card, names(1), v(1), ok)
      call d%check_magnitude(ic, 41, card, names(2), v(2), ok)
      if (.not. ok) return
      if (edges) then
         ks = find_edge_set(m, name)
         if (ks == 0) call d%error_at(ic, 11, 'E-GROUP', &
                                      card//': GROUP "'//name//'" is no edge set (physical '// &
                                      'curve) of the mesh; known: '//set_names(m, .true.))
      else
         ks = find_node_set(m, name)
         if (ks == 0) call d%error_at(ic, 11, 'E-GROUP', &
                                      card//': GROUP "'//name//'" is no node set of the mesh; '// &
                                      'known: '//set_names(m, .false.))
      end if
      if (ks == 0) return
      if (icase < 1 .or. icase > MAX_CASE) then
         call d%error_at(ic, 51, 'E-RANGE', card//': CASE (columns 51-55) expected a load case '// &
                         '1..'//itoa(MAX_CASE)//', found '// &
                         itoa(icase))
         ks = 0
      end if
   end subroutine read_group_load_fields
end module group_cards
