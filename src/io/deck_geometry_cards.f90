!> The ELEMENTS, NODES and RESTRAINTS blocks of an input deck.
!!
!! Owns the element cards (connectivity and material numbers), the node cards
!! (coordinates; radius >= 0 in axisymmetry) and the restraint cards (fixed
!! directions, prescribed values and load cases, GROUP cards through
!! group_cards), each checked field by field against the counts of the
!! control card, with file, line and column (docs/deck-format.md).
module deck_geometry_cards
   use kinds, only: dp
   use strings, only: itoa, rtoa
   use deck_lexer, only: deck_t, shown
   use model, only: model_t, MAX_CASE, restraint_t, MAX_NODE, NTYPE_AXISYMMETRIC
   use group_cards, only: is_group_card, read_group_restraint, check_restraint_overlaps
   use deck_blocks, only: next_data_card, report_missing, check_tail
   implicit none
   private

   public :: read_elements, read_nodes, read_restraints

contains

   ! ------------------------------------------------------------------ ELEMENTS

   subroutine read_elements(d, ickw, m)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ickw
      type(model_t), intent(inout) :: m
      integer :: ic, ncards, ielem, imat, k, j, node(MAX_NODE), c1
      logical :: ok

      allocate (m%lnods(MAX_NODE, m%nelem), m%nnode_e(m%nelem), m%matno(m%nelem), &
                m%elem_line(m%nelem))
      m%lnods = 0
      m%nnode_e = m%nnode
      m%matno = 0
      m%elem_line = 0
      ncards = 0
      do
         ic = next_data_card(d, 'ELEMENTS', 'an element card (element number in columns 1-5)')
         if (ic == 0) exit
         ncards = ncards + 1
         ok = .true.
         call d%get_int(ic, 1, 5, 'ELEMENTS', 'IELEM', ielem, ok)
         call d%get_int(ic, 6, 10, 'ELEMENTS', 'MATNO', imat, ok)
         do k = 1, m%nnode
            c1 = 11 + 5*(k - 1)
            call d%get_int(ic, c1, c1 + 4, 'ELEMENTS', 'NODE'//itoa(k), node(k), ok)
         end do
         if (len_trim(d%field_text(ic, 11 + 5*m%nnode, 10000)) > 0) then
            call d%error_at(ic, 11 + 5*m%nnode, 'E-EXTRA', 'ELEMENTS: NNODE = '//itoa(m%nnode)// &
                            ' on the control card, but the card has more fields: "'// &
                            shown(trim(adjustl(d%field_text(ic, 11 + 5*m%nnode, 10000))))//'"')
            ok = .false.
         end if
         if (.not. ok) cycle
         if (ielem < 1 .or. ielem > m%nelem) then
            call d%error_at(ic, 1, 'E-RANGE', 'ELEMENTS: element number (columns 1-5) expected '// &
                            '1..'//itoa(m%nelem)//' (NELEM), found '//itoa(ielem))
            cycle
         end if
         if (m%elem_line(ielem) /= 0) then
            call d%error_at(ic, 1, 'E-DUPLICATE', 'ELEMENTS: element '//itoa(ielem)// &
                            ' is defined twice (first on line '//itoa(m%elem_line(ielem))//')')
            cycle
         end if
         if (imat < 1 .or. imat > m%nmats) then
            call d%error_at(ic, 6, 'E-RANGE', 'ELEMENTS: material number MATNO (columns 6-10) '// &
                            'expected 1..'//itoa(m%nmats)//' (NMATS), found '//itoa(imat))
            ok = .false.
         end if
         do k = 1, m%nnode
            c1 = 11 + 5*(k - 1)
            if (node(k) < 1 .or. node(k) > m%npoin) then
               call d%error_at(ic, c1, 'E-RANGE', 'ELEMENTS: NODE'//itoa(k)//' (columns '// &
                               itoa(c1)//'-'//itoa(c1 + 4)//') expected a node number 1..'// &
                               itoa(m%npoin)//' (NPOIN), found '//itoa(node(k)))
               ok = .false.
            end if
            do j = 1, k - 1
               if (node(j) == node(k)) then
                  call d%error_at(ic, c1, 'E-ELEMENT', 'ELEMENTS: node '//itoa(node(k))// &
                                  ' appears twice in element '//itoa(ielem))
                  ok = .false.
               end if
            end do
         end do
         m%elem_line(ielem) = d%cards(ic)%line
         if (.not. ok) cycle
         m%lnods(1:m%nnode, ielem) = node(1:m%nnode)
         m%matno(ielem) = imat
      end do
      if (ncards /= m%nelem) then
         call d%error_at(ickw, 1, 'E-COUNT', 'ELEMENTS: NELEM = '//itoa(m%nelem)// &
                         ' on the control card, but the block has '//itoa(ncards)//' cards')
      else
         call report_missing(d, ickw, 'ELEMENTS', 'element', m%elem_line)
      end if
   end subroutine read_elements

   ! ------------------------------------------------------------------ NODES

   subroutine read_nodes(d, ickw, m)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ickw
      type(model_t), intent(inout) :: m
      integer :: ic, ncards, ipoin
      real(dp) :: x, y
      logical :: ok

      allocate (m%coord(2, m%npoin), m%node_line(m%npoin))
      m%coord = 0.0_dp
      m%node_line = 0
      ncards = 0
      do
         ic = next_data_card(d, 'NODES', 'a node card (node number in columns 1-5)')
         if (ic == 0) exit
         ncards = ncards + 1
         ok = .true.
         call d%get_int(ic, 1, 5, 'NODES', 'IPOIN', ipoin, ok)
         call d%get_real(ic, 6, 15, 'NODES', 'X', x, ok)
         call d%get_real(ic, 16, 25, 'NODES', 'Y', y, ok)
         call d%check_coordinate(ic, 6, 'NODES', 'X', x, ok)
         call d%check_coordinate(ic, 16, 'NODES', 'Y', y, ok)
         if (len_trim(d%field_text(ic, 26, 10000)) > 0) then
            call d%error_at(ic, 26, 'E-EXTRA', 'NODES: expected IPOIN, X, Y in columns 1-25, '// &
                            'found more: "'//shown(trim(adjustl(d%field_text(ic, 26, 10000))))// &
                            '"')
            ok = .false.
         end if
         if (.not. ok) cycle
         if (ipoin < 1 .or. ipoin > m%npoin) then
            call d%error_at(ic, 1, 'E-RANGE', 'NODES: node number (columns 1-5) expected 1..'// &
                            itoa(m%npoin)//' (NPOIN), found '//itoa(ipoin))
            cycle
         end if
         if (m%node_line(ipoin) /= 0) then
            call d%error_at(ic, 1, 'E-DUPLICATE', 'NODES: node '//itoa(ipoin)// &
                            ' is defined twice (first on line '//itoa(m%node_line(ipoin))//')')
            cycle
         end if
         if (m%ntype == NTYPE_AXISYMMETRIC .and. x < 0.0_dp) then
            call d%error_at(ic, 6, 'E-RANGE', 'NODES: axisymmetric analysis needs radius X >= '// &
                            '0 (columns 6-15), found '//rtoa(x))
         end if
         m%node_line(ipoin) = d%cards(ic)%line
         m%coord(:, ipoin) = [x, y]
      end do
      if (ncards /= m%npoin) then
         call d%error_at(ickw, 1, 'E-COUNT', 'NODES: NPOIN = '//itoa(m%npoin)// &
                         ' on the control card, but the block has '//itoa(ncards)//' cards')
      else
         call report_missing(d, ickw, 'NODES', 'node', m%node_line)
      end if
   end subroutine read_nodes

   ! ------------------------------------------------------------------ RESTRAINTS

   subroutine read_restraints(d, ickw, m, nvfix)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ickw
      type(model_t), intent(inout) :: m
      integer, intent(in) :: nvfix            !! NVFIX of the control card: the number of cards
      type(restraint_t), allocatable :: list(:)
      integer, allocatable :: first_line(:)
      integer :: ic, n, node, code, icase, ngroup, ngroup_entries, k0
      real(dp) :: ux, uy
      logical :: ok

      ngroup = 0        ! GROUP cards, and the restraint entries they gave
      ngroup_entries = 0
      allocate (list(max(nvfix, 0) + 16), first_line(m%npoin))
      first_line = 0
      n = 0
      do
         ic = next_data_card(d, 'RESTRAINTS', 'a restraint card (node number in columns 1-5)', &
                             allow_group=.true.)
         if (ic == 0) exit
         if (is_group_card(d, ic)) then
            ngroup = ngroup + 1
            k0 = n
            call read_group_restraint(d, ic, m, list, n)
            ngroup_entries = ngroup_entries + (n - k0)
            cycle
         end if
         ok = .true.
         call d%get_int(ic, 1, 5, 'RESTRAINTS', 'NODE', node, ok)
         call d%get_int(ic, 6, 10, 'RESTRAINTS', 'CODE', code, ok)
         call d%get_real(ic, 11, 20, 'RESTRAINTS', 'UX', ux, ok, default=0.0_dp)
         call d%get_real(ic, 21, 30, 'RESTRAINTS', 'UY', uy, ok, default=0.0_dp)
         call d%get_int(ic, 31, 35, 'RESTRAINTS', 'CASE', icase, ok, default=1)
         call check_tail(d, ic, 36, 'RESTRAINTS', 'NODE, CODE, UX, UY, CASE in columns 1-35', ok)
         call d%check_magnitude(ic, 11, 'RESTRAINTS', 'UX', ux, ok)
         call d%check_magnitude(ic, 21, 'RESTRAINTS', 'UY', uy, ok)
         if (n >= size(list)) list = [list, list]
         n = n + 1
         list(n) = restraint_t()
         if (.not. ok) cycle
         if (node < 1 .or. node > m%npoin) then
            call d%error_at(ic, 1, 'E-RANGE', 'RESTRAINTS: NODE (columns 1-5) expected a node '// &
                            'number 1..'//itoa(m%npoin)//', found '//itoa(node))
            cycle
         end if
         if (all(code /= [1, 10, 11])) then
            call d%error_at(ic, 6, 'E-CODE', 'RESTRAINTS: CODE (columns 6-10) expected 10 (x '// &
                            'fixed), 01 (y fixed) or 11 (both), found '//itoa(code))
            cycle
         end if
         if (icase < 1 .or. icase > MAX_CASE) then
            call d%error_at(ic, 31, 'E-RANGE', 'RESTRAINTS: CASE (columns 31-35) expected a '// &
                            'load case 1..'//itoa(MAX_CASE)//', found '//itoa(icase))
            cycle
         end if
         if (first_line(node) /= 0) then
            call d%error_at(ic, 1, 'E-DUPLICATE', 'RESTRAINTS: node '//itoa(node)// &
                            ' is restrained twice (first on line '//itoa(first_line(node))// &
                            '); give one card with CODE 11')
            cycle
         end if
         first_line(node) = d%cards(ic)%line
         list(n)%node = node
         list(n)%fixed = [code >= 10, mod(code, 10) == 1]
         list(n)%value = [ux, uy]
         if (.not. list(n)%fixed(1) .and. abs(ux) > 0.0_dp) call d%error_at(ic, 11, 'E-CODE', &
               'RESTRAINTS: UX = '//rtoa(ux)//' is prescribed but CODE '//itoa(code)// &
               ' leaves x free')
         if (.not. list(n)%fixed(2) .and. abs(uy) > 0.0_dp) call d%error_at(ic, 21, 'E-CODE', &
               'RESTRAINTS: UY = '//rtoa(uy)//' is prescribed but CODE '//itoa(code)// &
               ' leaves y free')
         list(n)%icase = icase
         list(n)%line = d%cards(ic)%line
      end do
      if (n - ngroup_entries + ngroup /= nvfix) then
         call d%error_at(ickw, 1, 'E-COUNT', 'RESTRAINTS: NVFIX = '//itoa(nvfix)// &
                         ' on the control card, but the block has '// &
                         itoa(n - ngroup_entries + ngroup)//' cards')
      end if
      m%fixes = pack(list(1:n), list(1:n)%node > 0)
      if (ngroup > 0) call check_restraint_overlaps(d, m, m%fixes)
   end subroutine read_restraints

end module deck_geometry_cards
