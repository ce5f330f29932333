!> LOADS/PRETENSION: bolt preload across a section of a body (see
!! docs/deck-format.md, "LOADS", and docs/bolts.md).
!!
!!     PRETENSION
!!     #         section             AXIS     FORCE CASE MODE
!!     GROUP     shank                  Y    1000.0    2 LOCK
!!     SECTION   bolt                   Y    1000.0    2
!!        21   22   23                                  (node numbers, 16 x I5)
!!
!! GROUP names a node set of the mesh (a physical curve across the body);
!! SECTION gives the section a label and its nodes on the data cards that
!! follow.  AXIS X or Y (Y, i.e. z, in axisymmetry), FORCE the preload at
!! factor 1 (tension positive), CASE its load case (blank 1), MODE LOCK (the
!! default: increments that hold the case's factor keep the section's
!! shortening) or FORCE (they keep the force).  The reader stores what the
!! cards say; pretension_section builds the section.
module pretension_cards
   use kinds, only: dp
   use strings, only: itoa, same_name
   use deck_lexer, only: deck_t, shown
   use model, only: model_t, MAX_CASE, find_node_set, NTYPE_AXISYMMETRIC
   use pretension, only: pretension_t, PRETENSION_LOCK, PRETENSION_FORCE
   implicit none
   private
   public :: is_pretension_card, read_pretension_card, read_pretension_nodes, finish_pretensions

contains

   !> A card whose first word is GROUP or SECTION.
   logical function is_pretension_card(d, ic)
      type(deck_t), intent(in) :: d
      integer, intent(in) :: ic
      is_pretension_card = .false.
      if (.not. d%is_keyword_card(ic)) return
      is_pretension_card = d%keyword(ic) == 'GROUP' .or. d%keyword(ic) == 'SECTION'
   end function is_pretension_card

   !> A GROUP or SECTION card: appended to pts (a bad card is reported and
   !! appended with line 0, so that its node cards are not mistaken for others).
   subroutine read_pretension_card(d, ic, m, pts)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(model_t), intent(in) :: m
      type(pretension_t), allocatable, intent(inout) :: pts(:)
      character(len=*), parameter :: card = 'LOADS/PRETENSION'
      type(pretension_t) :: p
      character(len=:), allocatable :: word, ax, mode
      logical :: ok
      integer :: k, is

      ok = .true.
      word = d%keyword(ic)
      p%group = word == 'GROUP'
      p%name = trim(adjustl(d%field_text(ic, 11, 30)))
      if (len(p%name) == 0) then
         call d%error_at(ic, 11, 'E-MISSING', card// &
                         ': field NAME (columns 11-30) expected the section''s '// &
                         'name, found a blank field')
         ok = .false.
      end if
      call d%get_word(ic, 31, 35, card, 'AXIS', ax, ok)
      call d%get_real(ic, 36, 45, card, 'FORCE', p%force, ok)
      call d%get_int(ic, 46, 50, card, 'CASE', p%icase, ok, default=1)
      call d%get_word(ic, 51, 60, card, 'MODE', mode, ok, default='LOCK')
      if (ok .and. len_trim(d%field_text(ic, 61, 100000)) > 0) then
         call d%error_at(ic, 61, 'E-EXTRA', card// &
                         ': expected NAME, AXIS, FORCE, CASE, MODE in columns 11-60, '// &
                         'found more: "'//shown(trim(adjustl(d%field_text(ic, 61, 100000))))//'"')
         ok = .false.
      end if
      if (ok) call d%check_magnitude(ic, 36, card, 'FORCE', p%force, ok)
      if (ok) then
         select case (ax)
         case ('X')
            p%axis = 1
         case ('Y')
            p%axis = 2
         case default
            call d%error_at(ic, 31, 'E-RANGE', card// &
                            ': AXIS (columns 31-35) expected X or Y, found "'//shown(ax)//'"')
            ok = .false.
         end select
         if (ok .and. m%ntype == NTYPE_AXISYMMETRIC .and. p%axis /= 2) then
            call d%error_at(ic, 31, 'E-RANGE', card// &
                            ': AXIS (columns 31-35) expected Y (the axis z) in an '// &
                            'axisymmetric analysis, found "'//shown(ax)//'"')
            ok = .false.
         end if
      end if
      if (ok .and. (p%icase < 1 .or. p%icase > MAX_CASE)) then
         call d%error_at(ic, 46, 'E-RANGE', card// &
                         ': CASE (columns 46-50) expected a load case 1..'// &
                         itoa(MAX_CASE)//', found '//itoa(p%icase))
         ok = .false.
      end if
      if (ok) then
         select case (mode)
         case ('LOCK')
            p%mode = PRETENSION_LOCK
         case ('FORCE')
            p%mode = PRETENSION_FORCE
         case default
            call d%error_at(ic, 51, 'E-RANGE', card// &
                            ': MODE (columns 51-60) expected LOCK or FORCE, found "'// &
                            shown(mode)//'"')
            ok = .false.
         end select
      end if
      if (ok) then
         do k = 1, size(pts)
            if (pts(k)%line <= 0) cycle
            if (same_name(pts(k)%name, p%name)) then
               call d%error_at(ic, 11, 'E-DUPLICATE', &
                               card//': section "'//p%name//'" is given twice (first on '// &
                               'line '//itoa(pts(k)%line)//')')
               ok = .false.
            end if
         end do
      end if
      if (ok .and. p%group) then
         is = find_node_set(m, p%name)
         if (is == 0) then
            call d%error_at(ic, 11, 'E-GROUP', card//': GROUP "'//p%name// &
                            '" is no node set of the mesh'// &
                            ' (a SECTION card takes a node list)')
            ok = .false.
         else
            p%nodes = m%node_sets(is)%nodes
         end if
      end if
      if (.not. allocated(p%nodes)) allocate (p%nodes(0))
      p%line = merge(d%cards(ic)%line, 0, ok)
      pts = [pts, p]
   end subroutine read_pretension_card

   !> A data card of node numbers (16 x I5) after a SECTION card.
   subroutine read_pretension_nodes(d, ic, m, p)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(model_t), intent(in) :: m
      type(pretension_t), intent(inout) :: p
      integer :: k, node
      logical :: ok
      character(len=:), allocatable :: f
      do k = 1, 16
         f = trim(adjustl(d%field_text(ic, 5*k - 4, 5*k)))
         if (len(f) == 0) cycle
         ok = .true.
         call d%get_int(ic, 5*k - 4, 5*k, 'LOADS/PRETENSION', 'NODE', node, ok)
         if (.not. ok) cycle
         if (node < 1 .or. node > m%npoin) then
            call d%error_at(ic, 5*k - 4, 'E-RANGE', &
                            'LOADS/PRETENSION: NODE (columns '//itoa(5*k - 4)//'-'// &
                            itoa(5*k)//') expected a node number 1..'//itoa(m%npoin)// &
                            ', found '//itoa(node))
            cycle
         end if
         if (any(p%nodes == node)) then
            call d%error_at(ic, 5*k - 4, 'E-DUPLICATE', 'LOADS/PRETENSION: node '//itoa(node)// &
                            ' is listed twice in section "'//p%name//'"')
            cycle
         end if
         p%nodes = [p%nodes, node]
      end do
      if (len_trim(d%field_text(ic, 81, 100000)) > 0) then
         call d%error_at(ic, 81, 'E-EXTRA', &
                         'LOADS/PRETENSION: expected at most 16 node numbers (columns 1-80), '// &
                         'found more: "'//shown(trim(adjustl(d%field_text(ic, 81, 100000))))//'"')
      end if
   end subroutine read_pretension_nodes

   !> The sections read: a SECTION without nodes is reported at its card;
   !! cards that failed are dropped.
   subroutine finish_pretensions(d, pts, m)
      type(deck_t), intent(inout) :: d
      type(pretension_t), intent(in) :: pts(:)
      type(model_t), intent(inout) :: m
      integer :: k
      do k = 1, size(pts)
         if (pts(k)%line <= 0) cycle
         if (.not. pts(k)%group .and. size(pts(k)%nodes) < 2) then
            call d%errors%add('E-MISSING', 'LOADS/PRETENSION: SECTION "'//pts(k)%name// &
                              '" expected at least two '// &
                              'nodes on the data cards after it, found '// &
                              itoa(size(pts(k)%nodes)), &
                              file=d%file, line=pts(k)%line, col=11)
         end if
      end do
      m%pretensions = pack(pts, pts%line > 0)
   end subroutine finish_pretensions
end module pretension_cards
