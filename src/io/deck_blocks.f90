!> The block table of the deck format and the card helpers the block readers share.
!!
!! Owns the block keywords in their required order (`block_order`), whether a
!! card is a block keyword card, and the moves every block reader makes: the
!! next data card of a block (an unknown keyword reported once and skipped),
!! skipping to the next block, the surplus cards of a one-card block, the
!! numbers no card defined, and anything past the last field of a card.
!! Errors go to the deck's error list with file, line and column
!! (docs/deck-format.md).
module deck_blocks
   use strings, only: itoa
   use deck_lexer, only: deck_t, shown
   use group_cards, only: is_group_card
   implicit none
   private

   public :: block_order, block_index, is_block_card, skip_to_block, next_data_card
   public :: skip_extra, report_missing, check_tail

   !> Block keywords in their required order.
   character(len=10), parameter :: block_order(13) = [character(len=10) :: &
                                   'TITLE', 'CONTROL', 'OPTIONS', 'MESH', 'ELEMENTS', 'NODES', &
                                   'RESTRAINTS', 'TIES', 'MATERIALS', 'LOADS', 'CONTACT', &
                                   'INCREMENTS', 'END']

contains

   !> Consume data cards up to (not including) the next block keyword card.
   subroutine skip_to_block(d)
      type(deck_t), intent(inout) :: d
      integer :: ic
      do while (.not. d%at_end())
         ic = d%peek()
         if (is_block_card(d, ic)) exit
         ic = d%next()
      end do
   end subroutine skip_to_block

   !> Position of a keyword in `block_order` (0 if it is none).
   !! (A loop, not FINDLOC: gfortran 12 mis-compares deferred-length strings there.)
   pure integer function block_index(kw)
      character(len=*), intent(in) :: kw
      integer :: k
      block_index = 0
      do k = 1, size(block_order)
         if (trim(block_order(k)) == kw) then
            block_index = k
            return
         end if
      end do
   end function block_index

   logical function is_block_card(d, ic)
      type(deck_t), intent(in) :: d
      integer, intent(in) :: ic
      is_block_card = .false.
      if (.not. d%is_keyword_card(ic)) return
      is_block_card = block_index(d%keyword(ic)) > 0
   end function is_block_card

   !> Next data card of the current block, or 0 at the next block keyword.
   !! A card that starts with a letter but is no block keyword is reported.
   integer function next_data_card(d, card, expected, allow_group) result(ic)
      type(deck_t), intent(inout) :: d
      character(len=*), intent(in) :: card      !! card name
      character(len=*), intent(in) :: expected  !! what its first field holds
      logical, intent(in), optional :: allow_group  !! GROUP cards are data cards here
      !! (see group_cards)
      ic = 0
      do while (.not. d%at_end())
         if (is_block_card(d, d%peek())) return
         ic = d%next()
         if (present(allow_group)) then
            if (allow_group .and. is_group_card(d, ic)) return
         end if
         if (d%is_keyword_card(ic)) then
            ! an unknown keyword: report it once and skip its cards
            call d%error_at(ic, 1, 'E-BLOCK', card//': expected '//expected// &
                            ' or a block keyword (TITLE, CONTROL, OPTIONS, MESH, ELEMENTS, '// &
                            'NODES, RESTRAINTS, TIES, MATERIALS, LOADS, CONTACT, INCREMENTS, '// &
                            'END), found "'//shown(trim(d%cards(ic)%text))//'"')
            call skip_to_block(d)
            ic = 0
            return
         end if
         return
      end do
   end function next_data_card

   !> Report surplus cards of a one-card block.
   subroutine skip_extra(d, card)
      type(deck_t), intent(inout) :: d
      character(len=*), intent(in) :: card
      integer :: ic
      do while (.not. d%at_end())
         ic = d%peek()
         if (is_block_card(d, ic)) exit
         ic = d%next()
         call d%error_at(ic, 1, 'E-EXTRA', card//': block has one card only; unexpected card "'// &
                         shown(trim(d%cards(ic)%text))//'"')
      end do
   end subroutine skip_extra

   !> Name the numbers 1..n that no card defined.
   subroutine report_missing(d, ickw, card, what, line_of)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ickw
      character(len=*), intent(in) :: card, what
      integer, intent(in) :: line_of(:)
      integer :: i, nmiss
      character(len=:), allocatable :: list
      nmiss = 0
      list = ''
      do i = 1, size(line_of)
         if (line_of(i) == 0) then
            nmiss = nmiss + 1
            if (nmiss <= 10) list = list//' '//itoa(i)
         end if
      end do
      if (nmiss > 10) list = list//' ...'
      if (nmiss > 0) call d%error_at(ickw, 1, 'E-MISSING', card//': no card defines '//what// &
                                     '(s)'//list)
   end subroutine report_missing

   !> Anything past the last field of a card is an error.
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

end module deck_blocks
