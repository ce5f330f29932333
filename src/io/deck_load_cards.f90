!> The LOADS and INCREMENTS blocks of an input deck: the loads and their history.
!!
!! Owns the sub-blocks of LOADS (POINT, EDGE, BODY cards, GROUP cards through
!! group_cards, PRETENSION through pretension_cards; an edge load located on
!! its element's edge, its direction following the element's orientation) and
!! the load history of INCREMENTS (the factor of every load case ramped
!! linearly card by card).  Errors with file, line and column
!! (docs/deck-format.md).
module deck_load_cards
   use kinds, only: dp
   use strings, only: itoa, rtoa
   use deck_lexer, only: deck_t, shown
   use model, only: model_t, MAX_CASE, point_load_t, edge_load_t, body_load_t
   use topology, only: element_edge_nodes, nedges
   use pretension, only: pretension_t
   use pretension_cards, only: is_pretension_card, read_pretension_card, read_pretension_nodes, &
                               finish_pretensions
   use group_cards, only: is_group_card, read_group_point_load, read_group_edge_load
   use deck_blocks, only: is_block_card, next_data_card, check_tail
   implicit none
   private

   public :: read_loads, read_point_load, read_edge_load, read_body_load, read_increments

contains

   ! ------------------------------------------------------------------ LOADS

   subroutine read_loads(d, m)
      type(deck_t), intent(inout) :: d
      type(model_t), intent(inout) :: m
      integer :: ic
      character(len=:), allocatable :: sub
      type(point_load_t), allocatable :: pl(:)
      type(edge_load_t), allocatable :: el(:)
      type(body_load_t), allocatable :: bl(:)
      integer :: npl, nel, nbl
      type(pretension_t), allocatable :: pts(:)

      allocate (pl(16), el(16), bl(4), pts(0))
      npl = 0
      nel = 0
      nbl = 0
      sub = ''
      do while (.not. d%at_end())
         ic = d%peek()
         if (is_block_card(d, ic)) exit
         ic = d%next()
         if (is_group_card(d, ic) .and. (sub == 'POINT' .or. sub == 'EDGE')) then
            if (sub == 'POINT') call read_group_point_load(d, ic, m, pl, npl)
            if (sub == 'EDGE') call read_group_edge_load(d, ic, m, el, nel)
            cycle
         end if
         if (sub == 'PRETENSION' .and. is_pretension_card(d, ic)) then
            call read_pretension_card(d, ic, m, pts)
            cycle
         end if
         if (d%is_keyword_card(ic)) then
            sub = d%keyword(ic)
            if (all(sub /= [character(len=10) :: 'POINT', 'EDGE', 'BODY', 'PRETENSION'])) then
               call d%error_at(ic, 1, 'E-CARD', 'LOADS: expected a sub-block keyword POINT, '// &
                               'EDGE, BODY or PRETENSION, or a load card, found "'// &
                               shown(trim(d%cards(ic)%text))//'"')
               sub = 'BAD'
            end if
            cycle
         end if
         select case (sub)
         case ('POINT')
            if (npl >= size(pl)) pl = [pl, pl]
            npl = npl + 1
            call read_point_load(d, ic, m, pl(npl))
         case ('EDGE')
            if (.not. allocated(m%nnode_e)) then
               ! the card names an element, and no element was read
               call d%error_at(ic, 1, 'E-CARD', 'LOADS/EDGE: an edge load refers to element '// &
                               'numbers, but no elements were read (the ELEMENTS block is '// &
                               'missing or was rejected)')
               sub = 'BAD'
               cycle
            end if
            if (nel >= size(el)) el = [el, el]
            nel = nel + 1
            call read_edge_load(d, ic, m, el(nel))
         case ('PRETENSION')
            if (size(pts) == 0) then
               call d%error_at(ic, 1, 'E-CARD', 'LOADS/PRETENSION: expected a GROUP or SECTION '// &
                               'card, found "'//shown(trim(d%cards(ic)%text))//'"')
               sub = 'BAD'
            else if (pts(size(pts))%group) then
               if (pts(size(pts))%line > 0) call d%error_at(ic, 1, 'E-CARD', &
                     'LOADS/PRETENSION: node numbers follow a SECTION card only (a GROUP takes '// &
                     'the nodes of its set), found "'//shown(trim(d%cards(ic)%text))//'"')
            else
               call read_pretension_nodes(d, ic, m, pts(size(pts)))
            end if
         case ('BODY')
            if (nbl >= size(bl)) bl = [bl, bl]
            nbl = nbl + 1
            call read_body_load(d, ic, m, bl(nbl))
         case ('')
            call d%error_at(ic, 1, 'E-CARD', 'LOADS: a load card must follow a sub-block '// &
                            'keyword POINT, EDGE or BODY, found "'// &
                            shown(trim(d%cards(ic)%text))//'"')
            sub = 'BAD'
         case default
            continue   ! cards under a bad sub-block keyword were already reported
         end select
      end do
      m%point_loads = pack(pl(1:npl), pl(1:npl)%node > 0)
      m%edge_loads = pack(el(1:nel), el(1:nel)%ielem > 0)
      m%body_loads = pack(bl(1:nbl), bl(1:nbl)%line > 0)
      call finish_pretensions(d, pts, m)
   end subroutine read_loads

   subroutine read_point_load(d, ic, m, p)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(model_t), intent(in) :: m
      type(point_load_t), intent(out) :: p
      integer :: node, icase
      real(dp) :: fx, fy
      logical :: ok
      ok = .true.
      call d%get_int(ic, 1, 5, 'LOADS/POINT', 'NODE', node, ok)
      call d%get_real(ic, 6, 15, 'LOADS/POINT', 'FX', fx, ok, default=0.0_dp)
      call d%get_real(ic, 16, 25, 'LOADS/POINT', 'FY', fy, ok, default=0.0_dp)
      call d%get_int(ic, 26, 30, 'LOADS/POINT', 'CASE', icase, ok, default=1)
      call check_tail(d, ic, 31, 'LOADS/POINT', 'NODE, FX, FY, CASE in columns 1-30', ok)
      call d%check_magnitude(ic, 6, 'LOADS/POINT', 'FX', fx, ok)
      call d%check_magnitude(ic, 16, 'LOADS/POINT', 'FY', fy, ok)
      if (.not. ok) return
      if (node < 1 .or. node > m%npoin) then
         call d%error_at(ic, 1, 'E-RANGE', 'LOADS/POINT: NODE (columns 1-5) expected a node '// &
                         'number 1..'//itoa(m%npoin)//', found '//itoa(node))
         return
      end if
      if (icase < 1 .or. icase > MAX_CASE) then
         call d%error_at(ic, 26, 'E-RANGE', 'LOADS/POINT: CASE (columns 26-30) expected a load '// &
                         'case 1..'//itoa(MAX_CASE)//', found '//itoa(icase))
         return
      end if
      p = point_load_t(node=node, force=[fx, fy], icase=icase, line=d%cards(ic)%line)
   end subroutine read_point_load

   subroutine read_edge_load(d, ic, m, e)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(model_t), intent(in) :: m
      type(edge_load_t), intent(out) :: e
      integer :: ielem, nd(3), icase, nn, k, iedge, loc(3), nloc, nnode, a, b, mid
      real(dp) :: pn(3), pt(3)
      logical :: ok, found
      character(len=*), parameter :: card = 'LOADS/EDGE'

      ok = .true.
      call d%get_int(ic, 1, 5, card, 'IELEM', ielem, ok)
      call d%get_int(ic, 6, 10, card, 'N1', nd(1), ok)
      call d%get_int(ic, 11, 15, card, 'N2', nd(2), ok)
      call d%get_int(ic, 16, 20, card, 'N3', nd(3), ok, default=0)
      do k = 1, 3
         call d%get_real(ic, 11 + 10*k, 20 + 10*k, card, 'PN'//itoa(k), pn(k), ok, default=0.0_dp)
      end do
      do k = 1, 3
         call d%get_real(ic, 41 + 10*k, 50 + 10*k, card, 'PT'//itoa(k), pt(k), ok, default=0.0_dp)
      end do
      call d%get_int(ic, 81, 85, card, 'CASE', icase, ok, default=1)
      call check_tail(d, ic, 86, card, 'IELEM, N1-N3, PN1-PN3, PT1-PT3, CASE in columns 1-85', ok)
      do k = 1, 3
         call d%check_magnitude(ic, 11 + 10*k, card, 'PN'//itoa(k), pn(k), ok)
         call d%check_magnitude(ic, 41 + 10*k, card, 'PT'//itoa(k), pt(k), ok)
      end do
      if (.not. ok) return
      if (ielem < 1 .or. ielem > m%nelem) then
         call d%error_at(ic, 1, 'E-RANGE', card//': IELEM (columns 1-5) expected an element '// &
                         'number 1..'//itoa(m%nelem)//', found '//itoa(ielem))
         return
      end if
      if (icase < 1 .or. icase > MAX_CASE) then
         call d%error_at(ic, 81, 'E-RANGE', card//': CASE (columns 81-85) expected a load case '// &
                         '1..'//itoa(MAX_CASE)//', found '// &
                         itoa(icase))
         return
      end if
      nnode = m%nnode_e(ielem)
      nn = merge(3, 2, nd(3) /= 0)
      if (nnode >= 8 .and. nn == 2) then
         call d%error_at(ic, 16, 'E-EDGE', card//': element '//itoa(ielem)// &
                         ' has quadratic edges: expected N1 (corner), N2 (midside), N3 '// &
                         '(corner), found only two nodes')
         return
      end if
      if (nnode < 8 .and. nn == 3) then
         call d%error_at(ic, 16, 'E-EDGE', card//': element '//itoa(ielem)// &
                         ' has straight 2-node edges: expected N1, N2 and a blank N3, found N3 '// &
                         '= '//itoa(nd(3)))
         return
      end if
      if (any(m%lnods(1:nnode, ielem) == 0)) return   ! element card was bad, already reported
      ! corner nodes given by the user: first and last; midside: N2 of a quadratic edge
      a = nd(1)
      b = nd(nn)
      mid = 0
      if (nn == 3) mid = nd(2)
      found = .false.
      do iedge = 1, nedges(nnode)
         call element_edge_nodes(nnode, iedge, loc, nloc)
         associate (ga => m%lnods(loc(1), ielem), gb => m%lnods(loc(2), ielem))
            if (nn == 3) then
               if (m%lnods(loc(3), ielem) /= mid) cycle
            end if
            if (ga == a .and. gb == b) then
               found = .true.
               e%nodes(1:2) = [a, b]
               e%pn(1:2) = [pn(1), pn(nn)]
               e%pt(1:2) = [pt(1), pt(nn)]
            else if (ga == b .and. gb == a) then
               ! listed against the element's anticlockwise order: the user's
               ! tangential direction (first to last node) is reversed
               found = .true.
               e%nodes(1:2) = [b, a]
               e%pn(1:2) = [pn(nn), pn(1)]
               e%pt(1:2) = -[pt(nn), pt(1)]
            end if
         end associate
         if (found) exit
      end do
      if (.not. found) then
         if (nn == 3) then
            call d%error_at(ic, 6, 'E-EDGE', card//': nodes '//itoa(nd(1))//' '//itoa(nd(2))// &
                            ' '//itoa(nd(3))//' do not form an edge of element '//itoa(ielem)// &
                            ' (expected corner, midside, corner along one side)')
         else
            call d%error_at(ic, 6, 'E-EDGE', card//': nodes '//itoa(nd(1))//' '//itoa(nd(2))// &
                            ' do not form an edge of element '//itoa(ielem)// &
                            ' (expected the two corners of one side)')
         end if
         return
      end if
      if (nn == 3) then
         e%nodes(3) = mid
         e%pn(3) = pn(2)
         e%pt(3) = merge(pt(2), -pt(2), e%nodes(1) == a)
      end if
      e%ielem = ielem
      e%nn = nn
      e%icase = icase
      e%line = d%cards(ic)%line
   end subroutine read_edge_load

   subroutine read_body_load(d, ic, m, bl)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(model_t), intent(in) :: m
      type(body_load_t), intent(out) :: bl
      integer :: imat, icase
      real(dp) :: bx, by
      logical :: ok
      ok = .true.
      call d%get_int(ic, 1, 5, 'LOADS/BODY', 'MATNO', imat, ok, default=0)
      call d%get_real(ic, 6, 15, 'LOADS/BODY', 'BX', bx, ok, default=0.0_dp)
      call d%get_real(ic, 16, 25, 'LOADS/BODY', 'BY', by, ok, default=0.0_dp)
      call d%get_int(ic, 26, 30, 'LOADS/BODY', 'CASE', icase, ok, default=1)
      call check_tail(d, ic, 31, 'LOADS/BODY', 'MATNO, BX, BY, CASE in columns 1-30', ok)
      call d%check_magnitude(ic, 6, 'LOADS/BODY', 'BX', bx, ok)
      call d%check_magnitude(ic, 16, 'LOADS/BODY', 'BY', by, ok)
      if (.not. ok) return
      if (imat < 0 .or. imat > m%nmats) then
         call d%error_at(ic, 1, 'E-RANGE', 'LOADS/BODY: MATNO (columns 1-5) expected 0 (all) '// &
                         'or 1..'//itoa(m%nmats)//', found '//itoa(imat))
         return
      end if
      if (icase < 1 .or. icase > MAX_CASE) then
         call d%error_at(ic, 26, 'E-RANGE', 'LOADS/BODY: CASE (columns 26-30) expected a load '// &
                         'case 1..'//itoa(MAX_CASE)//', found '//itoa(icase))
         return
      end if
      bl = body_load_t(imat=imat, b=[bx, by], icase=icase, line=d%cards(ic)%line)
   end subroutine read_body_load

   ! ------------------------------------------------------------------ INCREMENTS

   !> Load history: each card (NSTEP, LAMBDA_1 .. LAMBDA_ncase) ramps the total
   !! factor of every load case linearly to its target in NSTEP equal
   !! increments; a blank target holds the previous value.
   subroutine read_increments(d, m)
      type(deck_t), intent(inout) :: d
      type(model_t), intent(inout) :: m
      integer :: ic, nstep, ncase, k, c1, i, nincs
      real(dp), allocatable :: target(:), prev(:), lam(:, :)
      real(dp) :: val
      logical :: ok

      ncase = max(1, &
                  maxval([1, m%fixes%icase, m%point_loads%icase, m%edge_loads%icase, &
                  m%body_loads%icase]))
      if (allocated(m%pretensions)) ncase = max(ncase, maxval([1, m%pretensions%icase]))
      m%ncase = ncase
      allocate (target(ncase), prev(ncase), lam(ncase, 0:64))
      lam = 0.0_dp
      prev = 0.0_dp
      nincs = 0
      do
         ic = next_data_card(d, 'INCREMENTS', 'an increment card (NSTEP in columns 1-5)')
         if (ic == 0) exit
         ok = .true.
         call d%get_int(ic, 1, 5, 'INCREMENTS', 'NSTEP', nstep, ok)
         target = prev
         do k = 1, ncase
            c1 = 6 + 10*(k - 1)
            call d%get_real(ic, c1, c1 + 9, 'INCREMENTS', 'LAMBDA'//itoa(k), val, ok, &
                            default=prev(k))
            ! the ramp from the previous factor takes differences: bounded so that they
            ! cannot overflow
            if (ok .and. abs(val) > 0.25_dp*huge(val)) then
               call d%error_at(ic, c1, 'E-RANGE', 'INCREMENTS: LAMBDA'//itoa(k)//' (columns '// &
                               itoa(c1)//'-'//itoa(c1 + 9)// &
                               ') expected a load factor of magnitude at most '// &
                               rtoa(0.25_dp*huge(val))//', found '//rtoa(val))
               ok = .false.
            end if
            target(k) = val
         end do
         call check_tail(d, ic, 6 + 10*ncase, 'INCREMENTS', 'NSTEP and '//itoa(ncase)// &
                         ' load factor(s), one per load case used by the deck', ok)
         if (.not. ok) cycle
         if (nstep < 1 .or. nstep > 100000) then
            call d%error_at(ic, 1, 'E-RANGE', 'INCREMENTS: NSTEP (columns 1-5) expected '// &
                            '1..100000 increments, found '//itoa(nstep))
            cycle
         end if
         if (nincs + nstep > ubound(lam, 2)) call grow(lam, nincs + nstep)
         do i = 1, nstep
            lam(:, nincs + i) = prev + (target - prev)*(real(i, dp)/real(nstep, dp))
         end do
         nincs = nincs + nstep
         prev = target
      end do
      if (nincs == 0) then
         call d%error_eof('E-INCREMENTS', 'INCREMENTS: the block has no increment cards; omit '// &
                          'the block for a single increment to load factor 1')
         return
      end if
      m%nincs = nincs
      allocate (m%lambda(ncase, 0:nincs))
      m%lambda = lam(:, 0:nincs)
   contains
      subroutine grow(a, nmin)
         real(dp), allocatable, intent(inout) :: a(:, :)
         integer, intent(in) :: nmin
         real(dp), allocatable :: t(:, :)
         allocate (t(size(a, 1), 0:max(nmin, 2*ubound(a, 2))))
         t = 0.0_dp
         t(:, 0:ubound(a, 2)) = a
         call move_alloc(t, a)
      end subroutine grow
   end subroutine read_increments

end module deck_load_cards
