!> What the readers of the CONTACT block share (docs/deck-format.md): the cursor that says
!! which data cards come next (set by the last keyword card: SURFACE, PAIRS or RIGID
!! POLYLINE), and the check that nothing follows a card's last field.
module deck_contact_fields
   use deck_lexer, only: deck_t, shown
   implicit none
   private
   public :: contact_cursor_t, check_tail
   public :: DATA_NONE, DATA_SURFACE, DATA_PAIRS, DATA_VERTICES

   ! What the data cards of the CONTACT block belong to: set by the last keyword card.
   integer, parameter :: DATA_NONE = 0       !! no data cards expected
   integer, parameter :: DATA_SURFACE = 1    !! node numbers of a SURFACE
   integer, parameter :: DATA_PAIRS = 2      !! explicit pairs after PAIRS
   integer, parameter :: DATA_VERTICES = 3   !! vertices of a RIGID POLYLINE

   !> Where the CONTACT reader is: the kind of data card expected next, and
   !! for DATA_SURFACE the side (1 A, 2 B) of the current interface.
   type :: contact_cursor_t
      integer :: mode = DATA_NONE
      integer :: iside = 0
      integer :: nif = 0            !! interfaces opened so far (cs%ifaces has room for more)
   end type contact_cursor_t

contains

   !> Anything past the last field of a CONTACT card is an error.
   subroutine check_tail(d, ic, col, what, ok)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic, col
      character(len=*), intent(in) :: what   !! the fields the card has
      logical, intent(inout) :: ok
      character(len=:), allocatable :: t
      t = trim(adjustl(d%field_text(ic, col, 100000)))
      if (len(t) > 0) then
         call d%error_at(ic, col, 'E-EXTRA', 'CONTACT: expected '//what//', found more: "'// &
            shown(t)//'"')
         ok = .false.
      end if
   end subroutine check_tail
end module deck_contact_fields
