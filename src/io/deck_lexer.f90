!> Card-level access to a fixed-format input deck.
!!
!! The whole file is read once into memory.  Blank lines and comments
!! (everything from a `#` to the end of the line) are dropped; every remaining
!! line is a *card* that remembers its line number, so that every error can be
!! reported as `file:line:col`.  Fields are fixed column ranges (I5 integers,
!! F10 reals accepting E-notation, A10 words), read by the `get_*` procedures,
!! which validate the text themselves instead of trusting a Fortran `read`
!! (which would silently accept "1 2" as 12 or stop the program on "abc").
module deck_lexer
   use, intrinsic :: ieee_exceptions, only: ieee_overflow, ieee_get_halting_mode, &
         ieee_set_halting_mode, &
                                            ieee_set_flag
   use kinds, only: dp
   use errors, only: error_list_t, printable
   use strings, only: upper, itoa, rtoa
   implicit none
   private

   public :: card_t, deck_t, is_integer_text, is_real_text, shown, MAX_DECK_BYTES, MAX_COORDINATE

   !> Largest coordinate (magnitude) of a node or a rigid profile: the geometry squares sums of
   !! coordinate differences (lengths, the element size squared), which must stay representable.
   real(dp), parameter :: MAX_COORDINATE = 0.25_dp*sqrt(huge(1.0_dp))

   !> Largest deck read (bytes): far above any mesh a fixed-format deck holds (5-digit node
   !> numbers).
   integer, parameter :: MAX_DECK_BYTES = 256*2**20

   !> One significant line of the deck.
   type :: card_t
      character(len=:), allocatable :: text  !! the line without comment and trailing blanks
      integer :: line = 0                    !! 1-based line number in the file
   end type card_t

   !> A deck held in memory, with a cursor and the list of errors found so far.
   type :: deck_t
      character(len=:), allocatable :: file  !! path as given by the user
      type(card_t), allocatable :: cards(:)
      integer :: ncard = 0
      integer :: pos = 0                     !! index of the last card consumed
      integer :: nlines = 0                  !! lines in the file
      integer :: last_format_error = 0       !! card of the last field-format error
      type(error_list_t) :: errors
   contains
      procedure :: load => deck_load
      procedure :: at_end => deck_at_end
      procedure :: peek => deck_peek
      procedure :: next => deck_next
      procedure :: keyword => deck_keyword
      procedure :: is_keyword_card => deck_is_keyword_card
      procedure :: get_int => deck_get_int
      procedure :: get_real => deck_get_real
      procedure :: get_word => deck_get_word
      procedure :: check_magnitude => deck_check_magnitude
      procedure :: check_coordinate => deck_check_coordinate
      procedure :: error_at => deck_error_at
      procedure :: error_eof => deck_error_eof
      procedure :: field_text => deck_field_text
   end type deck_t

contains

   !> Read the file into memory and split it into cards.
   !! A file that is not a text deck (a NUL byte: a binary file, /dev/zero,
   !! /dev/urandom) or is larger than MAX_DECK_BYTES is rejected with the
   !! line and column of the first offending byte; a file whose size the
   !! system does not report (a device, a pipe) is read byte by byte up to
   !! that limit.
   subroutine deck_load(this, path, ok)
      class(deck_t), intent(inout) :: this
      character(len=*), intent(in) :: path   !! deck file
      logical, intent(out) :: ok             !! false if the file could not be read
      integer :: u, ios, fsize, i, start, nl, nul
      character(len=:), allocatable :: buf
      character(len=256) :: msg
      logical :: exists

      this%file = path
      ok = .false.
      inquire (file=path, exist=exists)
      if (.not. exists) then
         call this%errors%add('E-FILE', 'cannot open deck: file "'//path//'" does not exist', &
                              file=path)
         return
      end if
      open (newunit=u, file=path, access='stream', form='unformatted', status='old', &
            action='read', iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call this%errors%add('E-FILE', 'cannot open deck: '//trim(msg), file=path)
         return
      end if
      call read_all(u, buf, fsize, ios, msg)
      close (u)
      if (ios /= 0) then
         call this%errors%add('E-FILE', 'cannot read deck: '//trim(msg), file=path)
         return
      end if
      nul = index(buf(1:fsize), achar(0))
      if (nul > 0 .or. fsize > MAX_DECK_BYTES) then
         if (nul == 0) nul = MAX_DECK_BYTES + 1
         nl = 1
         start = 1
         do i = 1, nul - 1
            if (buf(i:i) == achar(10)) then
               nl = nl + 1
               start = i + 1
            end if
         end do
         if (nul <= fsize .and. nul <= MAX_DECK_BYTES) then
            call this%errors%add('E-FILE', &
                                 'not a text deck: a NUL byte (binary data) at byte '//itoa(nul), &
                                 file=path, line=nl, col=nul - start + 1)
         else
            call this%errors%add('E-FILE', 'the deck is larger than '// &
                                 itoa(MAX_DECK_BYTES/2**20)// &
                                 ' MB: not a deck this program reads', file=path, line=nl, &
                                 col=nul - start + 1)
         end if
         return
      end if

      allocate (this%cards(64))
      this%ncard = 0
      nl = 0
      start = 1
      do i = 1, fsize + 1
         if (i > fsize) then
            if (start <= fsize) then
               nl = nl + 1
               call add_line(this, buf(start:fsize), nl)
            end if
            exit
         end if
         if (buf(i:i) == achar(10)) then
            nl = nl + 1
            call add_line(this, buf(start:i - 1), nl)
            start = i + 1
         end if
      end do
      this%nlines = nl
      this%pos = 0
      ok = .true.
   end subroutine deck_load

   !> The whole content of an open stream unit: read at once when the system
   !! reports the size, byte by byte (doubling the buffer) up to one byte past
   !! MAX_DECK_BYTES, or to the first NUL byte, when it does not.
   subroutine read_all(u, buf, n, ios, msg)
      integer, intent(in) :: u                          !! unit opened for stream access
      character(len=:), allocatable, intent(out) :: buf !! the content (buf(1:n))
      integer, intent(out) :: n                         !! bytes read
      integer, intent(out) :: ios                       !! 0, or the error of the read
      character(len=*), intent(inout) :: msg            !! the error message
      character(len=:), allocatable :: tmp
      character(len=1) :: c
      integer :: fsize
      inquire (unit=u, size=fsize)
      ios = 0
      if (fsize > 0) then
         n = min(fsize, MAX_DECK_BYTES + 1)
         allocate (character(len=n) :: buf)
         read (u, iostat=ios, iomsg=msg) buf
         return
      end if
      allocate (character(len=4096) :: buf)
      n = 0
      do while (n <= MAX_DECK_BYTES)
         read (u, iostat=ios, iomsg=msg) c
         if (ios /= 0) exit
         if (n == len(buf)) then
            allocate (character(len=2*len(buf)) :: tmp)
            tmp(1:n) = buf
            call move_alloc(tmp, buf)
         end if
         n = n + 1
         buf(n:n) = c
         if (c == achar(0)) exit
      end do
      if (is_iostat_end(ios)) ios = 0
   end subroutine read_all

   !> Strip CR, comment and trailing blanks; keep the line if anything is left.
   subroutine add_line(this, raw, nl)
      type(deck_t), intent(inout) :: this
      character(len=*), intent(in) :: raw
      integer, intent(in) :: nl
      character(len=:), allocatable :: s
      type(card_t), allocatable :: tmp(:)
      integer :: k

      s = raw
      if (len(s) > 0) then
         if (s(len(s):len(s)) == achar(13)) s = s(1:len(s) - 1)
      end if
      k = index(s, '#')
      if (k > 0) s = s(1:k - 1)
      k = index(s, achar(9))
      if (k > 0) then
         call this%errors%add('E-TAB', 'tab character in a fixed-format deck; '// &
                              'fields are counted in columns, use spaces', &
                              file=this%file, line=nl, col=k, card=shown(s, 200))
         s = expand_tabs(s)
      end if
      if (len_trim(s) == 0) return
      if (this%ncard >= size(this%cards)) then
         allocate (tmp(2*size(this%cards)))
         tmp(1:this%ncard) = this%cards(1:this%ncard)
         call move_alloc(tmp, this%cards)
      end if
      this%ncard = this%ncard + 1
      this%cards(this%ncard)%text = trim(s)
      this%cards(this%ncard)%line = nl
   end subroutine add_line

   !> Tabs expanded to the next multiple of 8 columns (two passes: the length, then the text).
   pure function expand_tabs(s) result(r)
      character(len=*), intent(in) :: s
      character(len=:), allocatable :: r
      integer :: i, n, k
      n = 0
      do i = 1, len(s)
         if (s(i:i) == achar(9)) then
            n = n + 8 - mod(n, 8)
         else
            n = n + 1
         end if
      end do
      allocate (character(len=n) :: r)
      n = 0
      do i = 1, len(s)
         if (s(i:i) == achar(9)) then
            k = 8 - mod(n, 8)
            r(n + 1:n + k) = repeat(' ', k)
            n = n + k
         else
            n = n + 1
            r(n:n) = s(i:i)
         end if
      end do
   end function expand_tabs

   !> Text of a card or field for a message: bytes outside printable ASCII
   !! shown as "?", and at most `limit` characters (default 60), "..." after.
   pure function shown(s, limit) result(r)
      character(len=*), intent(in) :: s
      integer, intent(in), optional :: limit
      character(len=:), allocatable :: r
      integer :: lim
      lim = 60
      if (present(limit)) lim = limit
      r = printable(s, max(lim, 0))
   end function shown

   pure logical function deck_at_end(this)
      class(deck_t), intent(in) :: this
      deck_at_end = this%pos >= this%ncard
   end function deck_at_end

   !> Index of the next card without consuming it (0 at the end).
   pure integer function deck_peek(this)
      class(deck_t), intent(in) :: this
      deck_peek = 0
      if (this%pos < this%ncard) deck_peek = this%pos + 1
   end function deck_peek

   !> Consume and return the index of the next card (0 at the end).
   integer function deck_next(this)
      class(deck_t), intent(inout) :: this
      deck_next = 0
      if (this%pos < this%ncard) then
         this%pos = this%pos + 1
         deck_next = this%pos
      end if
   end function deck_next

   !> The first blank-delimited word of card ic, upper-cased.
   function deck_keyword(this, ic) result(w)
      class(deck_t), intent(in) :: this
      integer, intent(in) :: ic
      character(len=:), allocatable :: w
      character(len=:), allocatable :: s
      integer :: k
      s = adjustl(this%cards(ic)%text)
      k = index(trim(s), ' ')
      if (k == 0) then
         w = upper(trim(s))
      else
         w = upper(s(1:k - 1))
      end if
   end function deck_keyword

   !> A keyword card starts with a letter in its first non-blank column.
   pure logical function deck_is_keyword_card(this, ic)
      class(deck_t), intent(in) :: this
      integer, intent(in) :: ic
      character(len=1) :: c
      character(len=:), allocatable :: s
      s = adjustl(this%cards(ic)%text)
      c = s(1:1)
      deck_is_keyword_card = (c >= 'A' .and. c <= 'Z') .or. (c >= 'a' .and. c <= 'z')
   end function deck_is_keyword_card

   !> The raw text of columns c1..c2 of card ic (blank-padded past the end).
   function deck_field_text(this, ic, c1, c2) result(f)
      class(deck_t), intent(in) :: this
      integer, intent(in) :: ic, c1, c2
      character(len=:), allocatable :: f
      integer :: n
      n = len(this%cards(ic)%text)
      if (c1 > n) then
         f = ''
      else
         f = this%cards(ic)%text(c1:min(c2, n))
      end if
   end function deck_field_text

   !> The tail of a number field's error where the text of the field before it runs on
   !! across column c1 (no blank at c1 - 1 and c1): a word or number one column too long,
   !! or shifted, which the fixed columns read as the start of this field.  Empty otherwise.
   function run_on_hint(this, ic, c1) result(h)
      class(deck_t), intent(in) :: this
      integer, intent(in) :: ic, c1
      character(len=:), allocatable :: h
      character(len=:), allocatable :: edge
      h = ''
      if (c1 <= 1) return
      edge = this%field_text(ic, c1 - 1, c1)
      if (len(edge) < 2) return
      if (edge(1:1) == ' ' .or. edge(2:2) == ' ') return
      h = ': the text of column '//itoa(c1 - 1)//' runs on into column '//itoa(c1)// &
          ' ("'//edge//'"); the fields are fixed columns (docs/deck-format.md): shorten or '// &
          'shift the entry before this field'
   end function run_on_hint

   !> Read an integer field.  Blank gives `default` when present, else an error.
   subroutine deck_get_int(this, ic, c1, c2, card, field, val, ok, default)
      class(deck_t), intent(inout) :: this
      integer, intent(in) :: ic          !! card index
      integer, intent(in) :: c1, c2      !! first and last column of the field
      character(len=*), intent(in) :: card   !! card name for messages
      character(len=*), intent(in) :: field  !! field name for messages
      integer, intent(out) :: val
      logical, intent(inout) :: ok       !! set to .false. on error, never set to .true.
      integer, intent(in), optional :: default
      character(len=:), allocatable :: f
      integer :: ios

      val = 0
      f = trim(adjustl(this%field_text(ic, c1, c2)))
      if (len(f) == 0) then
         if (present(default)) then
            val = default
         else
            call this%error_at(ic, c1, 'E-MISSING', card//': field '//field//' (columns '// &
                               itoa(c1)//'-'//itoa(c2)// &
                               ') expected an integer, found a blank field')
            ok = .false.
         end if
         return
      end if
      if (.not. is_integer_text(f)) then
         call this%error_at(ic, c1, 'E-NUMBER', card//': field '//field//' (columns '// &
                            itoa(c1)//'-'//itoa(c2)//') expected an integer, found "'// &
                            shown(f)//'"'//run_on_hint(this, ic, c1))
         ok = .false.
         return
      end if
      read (f, *, iostat=ios) val
      if (ios /= 0) then
         call this%error_at(ic, c1, 'E-NUMBER', card//': field '//field//' (columns '// &
                            itoa(c1)//'-'//itoa(c2)//') integer out of range: "'//shown(f)//'"')
         ok = .false.
      end if
   end subroutine deck_get_int

   !> Read a real field (plain or E-notation).  Blank gives `default` when present.
   subroutine deck_get_real(this, ic, c1, c2, card, field, val, ok, default)
      class(deck_t), intent(inout) :: this
      integer, intent(in) :: ic, c1, c2
      character(len=*), intent(in) :: card, field
      real(dp), intent(out) :: val
      logical, intent(inout) :: ok
      real(dp), intent(in), optional :: default
      character(len=:), allocatable :: f
      integer :: ios
      logical :: halt

      val = 0.0_dp
      f = trim(adjustl(this%field_text(ic, c1, c2)))
      if (len(f) == 0) then
         if (present(default)) then
            val = default
         else
            call this%error_at(ic, c1, 'E-MISSING', card//': field '//field//' (columns '// &
                               itoa(c1)//'-'//itoa(c2)// &
                               ') expected a real number, found a blank field')
            ok = .false.
         end if
         return
      end if
      if (.not. is_real_text(f)) then
         call this%error_at(ic, c1, 'E-NUMBER', card//': field '//field//' (columns '// &
                            itoa(c1)//'-'//itoa(c2)//') expected a real number, found "'// &
                            shown(f)//'"'//run_on_hint(this, ic, c1))
         ok = .false.
         return
      end if
      ! A literal beyond the range of real(dp) overflows inside the conversion;
      ! with overflow trapping on (Debug builds) that would stop the program
      ! before the range check below could report it as an input error.
      call ieee_get_halting_mode(ieee_overflow, halt)
      if (halt) call ieee_set_halting_mode(ieee_overflow, .false.)
      read (f, *, iostat=ios) val
      call ieee_set_flag(ieee_overflow, .false.)
      if (halt) call ieee_set_halting_mode(ieee_overflow, .true.)
      if (ios /= 0 .or. .not. (abs(val) <= huge(val))) then
         call this%error_at(ic, c1, 'E-NUMBER', card//': field '//field//' (columns '// &
                            itoa(c1)//'-'//itoa(c2)//') real number out of range: "'//shown(f)//'"')
         val = 0.0_dp
         ok = .false.
      end if
   end subroutine deck_get_real

   !> Read a word field (upper-cased).  Blank gives `default` when present.
   subroutine deck_get_word(this, ic, c1, c2, card, field, val, ok, default)
      class(deck_t), intent(inout) :: this
      integer, intent(in) :: ic, c1, c2
      character(len=*), intent(in) :: card, field
      character(len=:), allocatable, intent(out) :: val
      logical, intent(inout) :: ok
      character(len=*), intent(in), optional :: default
      val = upper(trim(adjustl(this%field_text(ic, c1, c2))))
      if (len(val) == 0) then
         if (present(default)) then
            val = default
         else
            call this%error_at(ic, c1, 'E-MISSING', card//': field '//field//' (columns '// &
                               itoa(c1)//'-'//itoa(c2)//') expected a word, found a blank field')
            ok = .false.
         end if
      end if
   end subroutine deck_get_word

   !> A load or a prescribed displacement read from columns c1.. of card ic
   !! must not exceed sqrt(huge) in magnitude: the analysis multiplies it by
   !! stiffnesses, which the material check bounds by sqrt(huge) as well, so
   !! that the product stays representable.  An error at the field otherwise.
   subroutine deck_check_magnitude(this, ic, c1, card, field, val, ok)
      class(deck_t), intent(inout) :: this
      integer, intent(in) :: ic, c1              !! card, first column of the field
      character(len=*), intent(in) :: card, field
      real(dp), intent(in) :: val
      logical, intent(inout) :: ok               !! set to .false. on error
      if (.not. ok) return
      if (abs(val) <= sqrt(huge(val))) return
      call this%error_at(ic, c1, 'E-RANGE', card//': '//field//' = '//rtoa(val)//' is beyond '// &
                         rtoa(sqrt(huge(val)))// &
                         ' in magnitude: the analysis multiplies it by stiffnesses')
      ok = .false.
   end subroutine deck_check_magnitude

   !> A coordinate (of a node, of a rigid profile) read from columns c1.. of
   !! card ic must not exceed MAX_COORDINATE in magnitude.
   subroutine deck_check_coordinate(this, ic, c1, card, field, val, ok)
      class(deck_t), intent(inout) :: this
      integer, intent(in) :: ic, c1              !! card, first column of the field
      character(len=*), intent(in) :: card, field
      real(dp), intent(in) :: val
      logical, intent(inout) :: ok               !! set to .false. on error
      if (.not. ok) return
      if (abs(val) <= MAX_COORDINATE) return
      call this%error_at(ic, c1, 'E-RANGE', card//': '//field//' = '//rtoa(val)//' is beyond '// &
                         rtoa(MAX_COORDINATE)//' in magnitude: the geometry squares lengths')
      ok = .false.
   end subroutine deck_check_coordinate

   !> Record an error located at card ic, column col.
   !! Only the first field-format error (E-NUMBER, E-MISSING, E-EXTRA) of a
   !! card is kept: a card in the wrong place would otherwise give one
   !! message per field.
   subroutine deck_error_at(this, ic, col, code, message)
      class(deck_t), intent(inout) :: this
      integer, intent(in) :: ic, col
      character(len=*), intent(in) :: code, message
      if (code == 'E-NUMBER' .or. code == 'E-MISSING' .or. code == 'E-EXTRA') then
         if (this%last_format_error == ic) return
         this%last_format_error = ic
      end if
      call this%errors%add(code, message, file=this%file, line=this%cards(ic)%line, &
                           col=max(col, 1), card=shown(this%cards(ic)%text, max(200, col + 20)))
   end subroutine deck_error_at

   !> Record an error at the end of the file (something is missing).
   subroutine deck_error_eof(this, code, message)
      class(deck_t), intent(inout) :: this
      character(len=*), intent(in) :: code, message
      call this%errors%add(code, message, file=this%file, line=max(this%nlines, 1))
   end subroutine deck_error_eof


   !> Optional sign followed by one or more digits.
   pure logical function is_integer_text(s)
      character(len=*), intent(in) :: s
      integer :: i, i0
      is_integer_text = .false.
      if (len(s) == 0) return
      i0 = 1
      if (s(1:1) == '+' .or. s(1:1) == '-') i0 = 2
      if (i0 > len(s)) return
      do i = i0, len(s)
         if (s(i:i) < '0' .or. s(i:i) > '9') return
      end do
      is_integer_text = .true.
   end function is_integer_text

   !> [sign] digits [. digits] [(e|E|d|D) [sign] digits], at least one mantissa digit.
   pure logical function is_real_text(s)
      character(len=*), intent(in) :: s
      integer :: i, n, nd
      is_real_text = .false.
      n = len(s)
      if (n == 0) return
      i = 1
      if (s(i:i) == '+' .or. s(i:i) == '-') i = i + 1
      nd = 0
      do while (i <= n)
         if (s(i:i) < '0' .or. s(i:i) > '9') exit
         nd = nd + 1
         i = i + 1
      end do
      if (i <= n) then
         if (s(i:i) == '.') then
            i = i + 1
            do while (i <= n)
               if (s(i:i) < '0' .or. s(i:i) > '9') exit
               nd = nd + 1
               i = i + 1
            end do
         end if
      end if
      if (nd == 0) return
      if (i <= n) then
         if (index('eEdD', s(i:i)) == 0) return
         i = i + 1
         if (i <= n) then
            if (s(i:i) == '+' .or. s(i:i) == '-') i = i + 1
         end if
         nd = 0
         do while (i <= n)
            if (s(i:i) < '0' .or. s(i:i) > '9') return
            nd = nd + 1
            i = i + 1
         end do
         if (nd == 0) return
      end if
      is_real_text = (i > n)
   end function is_real_text

end module deck_lexer
