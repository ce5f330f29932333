!> The lines of a gmsh `.msh` file, and the line and token readers of its sections.
!!
!! Owns `msh_text_t` (the whole file in memory, its line bounds and a cursor)
!! and the checked readers every section parser uses: a line of integers
!! (`read_ints`), the reals of a line (`line_reals`: finite, within
!! MAX_COORDINATE), a count bounded by the lines left (`check_count`), the
!! closing `$End<section>` (`expect_end`), and skipping an unused section.
!! Every error is E-GMSH with the .msh file and the line.  Knows no section.
module gmsh_text
      use, intrinsic :: ieee_exceptions, only: ieee_overflow, ieee_get_halting_mode, &
            ieee_set_halting_mode, ieee_set_flag
      use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use kinds, only: dp
   use errors, only: error_list_t
   use strings, only: itoa, rtoa
   use deck_lexer, only: MAX_COORDINATE
   implicit none
   private

   public :: msh_text_t, load, next_line, get_line, short
   public :: read_ints, check_count, tokens, is_int, line_reals
   public :: expect_end, skip_section

   !> Lines of the file with a cursor.
   type :: msh_text_t
      character(len=:), allocatable :: path
      character(len=:), allocatable :: buf            !! the whole file
      integer, allocatable :: lstart(:), lend(:)      !! bounds of each line in buf
      integer :: nlines = 0
      integer :: pos = 0                              !! last line consumed
   end type msh_text_t

contains

   !> Read the whole file; split it into lines.
   subroutine load(t, path, errors, ok)
      type(msh_text_t), intent(inout) :: t
      character(len=*), intent(in) :: path
      type(error_list_t), intent(inout) :: errors
      logical, intent(out) :: ok
      integer :: u, ios, fsize, i, n, s
      logical :: exists
      character(len=256) :: msg

      ok = .false.
      t%path = path
      inquire (file=path, exist=exists)
      if (.not. exists) then
         call errors%add('E-GMSH', 'cannot open mesh file "'//path//'": it does not exist', &
                         file=path)
         return
      end if
      open (newunit=u, file=path, access='stream', form='unformatted', status='old', &
            action='read', iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call errors%add('E-GMSH', 'cannot open mesh file: '//trim(msg), file=path)
         return
      end if
      inquire (unit=u, size=fsize)
      fsize = max(fsize, 0)
      allocate (character(len=fsize) :: t%buf)
      if (fsize > 0) read (u, iostat=ios, iomsg=msg) t%buf
      close (u)
      if (ios /= 0) then
         call errors%add('E-GMSH', 'cannot read mesh file: '//trim(msg), file=path)
         return
      end if
      n = 1
      do i = 1, fsize
         if (t%buf(i:i) == achar(10)) n = n + 1
      end do
      allocate (t%lstart(n), t%lend(n))
      n = 0
      s = 1
      do i = 1, fsize + 1
         if (i > fsize) then
            if (s <= fsize) then
               n = n + 1
               t%lstart(n) = s
               t%lend(n) = fsize
            end if
            exit
         end if
         if (t%buf(i:i) == achar(10)) then
            n = n + 1
            t%lstart(n) = s
            t%lend(n) = i - 1
            if (i - 1 >= s) then
               if (t%buf(i - 1:i - 1) == achar(13)) t%lend(n) = i - 2
            end if
            s = i + 1
         end if
      end do
      t%nlines = n
      t%pos = 0
      ok = .true.
   end subroutine load

   integer function next_line(t) result(il)
      type(msh_text_t), intent(inout) :: t
      il = 0
      if (t%pos >= t%nlines) return
      t%pos = t%pos + 1
      il = t%pos
   end function next_line

   function get_line(t, il) result(s)
      type(msh_text_t), intent(in) :: t
      integer, intent(in) :: il
      character(len=:), allocatable :: s
      if (il < 1 .or. il > t%nlines) then
         s = ''
      else
         s = t%buf(t%lstart(il):t%lend(il))
      end if
   end function get_line

   !> First 60 characters of a line, for messages.
   pure function short(s) result(r)
      character(len=*), intent(in) :: s
      character(len=:), allocatable :: r
      if (len(s) > 60) then
         r = s(1:60)//'...'
      else
         r = s
      end if
   end function short

   !> Next line of a section, split into integers (and reals when `reals` is given).
   !! Reports a truncated file or a line with the wrong number of values.
   subroutine read_ints(t, section, what, n, v, errors, ok, il, at_least)
      type(msh_text_t), intent(inout) :: t
      character(len=*), intent(in) :: section, what
      integer, intent(in) :: n                     !! number of integers expected
      integer, intent(out) :: v(:)
      type(error_list_t), intent(inout) :: errors
      logical, intent(inout) :: ok
      integer, intent(out) :: il
      logical, intent(in), optional :: at_least    !! more values than n are allowed
      character(len=:), allocatable :: line
      integer :: k, ios, nt
      integer :: b(2, 64)

      il = next_line(t)
      if (il == 0) then
         call errors%add('E-GMSH', 'truncated file: it ends inside $'//section//' (expected '// &
                         what//')', file=t%path, line=t%nlines)
         ok = .false.
         return
      end if
      line = get_line(t, il)
      call tokens(line, b, nt)
      if (nt < n .or. (nt > n .and. .not. present(at_least))) then
         if (nt >= 1) then
            if (line(b(1, 1):b(1, 1)) == '$') then
               call errors%add('E-GMSH', '$'//section//' ends early: expected '//what// &
                               ', found "'//short(trim(line))//'"', file=t%path, line=il)
               ok = .false.
               return
            end if
         end if
         call errors%add('E-GMSH', '$'//section//': expected '//what//' ('//itoa(n)// &
                         ' integers), found "'//short(trim(line))//'"', file=t%path, line=il)
         ok = .false.
         return
      end if
      do k = 1, n
         read (line(b(1, k):b(2, k)), *, iostat=ios) v(k)
         if (ios /= 0 .or. .not. is_int(line(b(1, k):b(2, k)))) then
            call errors%add('E-GMSH', '$'//section//': expected '//what//', found "'// &
                            line(b(1, k):b(2, k))//'" where an integer belongs', file=t%path, &
                            line=il)
            ok = .false.
            return
         end if
      end do
   end subroutine read_ints

   !> A count read from the file is bounded by what the file can still hold:
   !! `per` lines per entry after line il (a negative count is an error too),
   !! so that no array is sized from a count the file cannot back.
   subroutine check_count(t, section, what, n, per, il, errors, ok)
      type(msh_text_t), intent(in) :: t
      character(len=*), intent(in) :: section, what   !! section name, what is counted
      integer, intent(in) :: n                        !! the count
      integer, intent(in) :: per                      !! lines each entry takes at least
      integer, intent(in) :: il                       !! line of the count
      type(error_list_t), intent(inout) :: errors
      logical, intent(inout) :: ok
      if (.not. ok) return
      if (n < 0) then
         call errors%add('E-GMSH', '$'//section//': expected a number of '//what// &
                         ' >= 0, found '//itoa(n), file=t%path, line=il)
         ok = .false.
      else if (n > (t%nlines - il)/per) then
         call errors%add('E-GMSH', 'truncated file: it ends inside $'//section//' ('//itoa(n)// &
                         ' '//what//' declared, the file has only '//itoa(t%nlines - il)// &
                         ' more lines)', file=t%path, line=il)
         ok = .false.
      end if
   end subroutine check_count

   !> Blank-separated tokens of a line: bounds b(1:2, k), count nt (at most size(b, 2)).
   pure subroutine tokens(line, b, nt)
      character(len=*), intent(in) :: line
      integer, intent(out) :: b(:, :)
      integer, intent(out) :: nt
      integer :: i, n
      logical :: inword
      nt = 0
      inword = .false.
      n = len(line)
      do i = 1, n
         if (line(i:i) == ' ' .or. line(i:i) == achar(9)) then
            if (inword) b(2, nt) = i - 1
            inword = .false.
         else if (.not. inword) then
            if (nt == size(b, 2)) return
            nt = nt + 1
            b(1, nt) = i
            b(2, nt) = n
            inword = .true.
         end if
      end do
   end subroutine tokens

   pure logical function is_int(s)
      character(len=*), intent(in) :: s
      integer :: i, i0
      is_int = .false.
      if (len(s) == 0) return
      i0 = 1
      if (s(1:1) == '-' .or. s(1:1) == '+') i0 = 2
      if (i0 > len(s)) return
      do i = i0, len(s)
         if (s(i:i) < '0' .or. s(i:i) > '9') return
      end do
      is_int = .true.
   end function is_int

   !> Reals of a line (tokens first..first+n-1).
   subroutine line_reals(t, il, section, what, first, n, x, errors, ok)
      type(msh_text_t), intent(in) :: t
      integer, intent(in) :: il, first, n
      character(len=*), intent(in) :: section, what
      real(dp), intent(out) :: x(:)
      type(error_list_t), intent(inout) :: errors
      logical, intent(inout) :: ok
      character(len=:), allocatable :: line
      integer :: b(2, 64), nt, k, ios
      logical :: halt
      line = get_line(t, il)
      call tokens(line, b, nt)
      if (nt < first + n - 1) then
         call errors%add('E-GMSH', '$'//section//': expected '//what//', found "'// &
                         short(trim(line))//'"', file=t%path, line=il)
         ok = .false.
         return
      end if
      do k = 1, n
         associate (tok => line(b(1, first + k - 1):b(2, first + k - 1)))
            ! a literal beyond the range of real(dp) overflows inside the
            ! conversion: with overflow trapping on (Debug builds) that would stop
            ! the program before the check below could report it
            call ieee_get_halting_mode(ieee_overflow, halt)
            if (halt) call ieee_set_halting_mode(ieee_overflow, .false.)
            read (tok, *, iostat=ios) x(k)
            call ieee_set_flag(ieee_overflow, .false.)
            if (halt) call ieee_set_halting_mode(ieee_overflow, .true.)
            ! (ieee_is_finite: an ordered comparison with a NaN would trap in Debug builds)
            if (ios == 0) then
               if (.not. ieee_is_finite(x(k))) then
                  ! NaN, Inf, or out of range: every real read from a file is finite
                  call errors%add('E-GMSH', '$'//section//': expected '//what//', found "'// &
                                  short(tok)//'": not a finite number', file=t%path, line=il)
                  ok = .false.
               else if (abs(x(k)) > MAX_COORDINATE) then
                  call errors%add('E-GMSH', '$'//section//': expected '//what//', found "'// &
                                  short(tok)//'": beyond '//rtoa(MAX_COORDINATE)// &
                                  ' in magnitude (the geometry squares lengths)', file=t%path, &
                                  line=il)
                  ok = .false.
               end if
               if (.not. ok) then
                  x(k) = 0.0_dp
                  return
               end if
            end if
         end associate
         if (ios /= 0) then
            call errors%add('E-GMSH', '$'//section//': expected '//what//', found "'// &
                            line(b(1, first + k - 1):b(2, first + k - 1))// &
                            '" where a number belongs', file=t%path, line=il)
            ok = .false.
            return
         end if
      end do
   end subroutine line_reals

   !> The closing $End<section> line.
   subroutine expect_end(t, section, errors, ok)
      type(msh_text_t), intent(inout) :: t
      character(len=*), intent(in) :: section
      type(error_list_t), intent(inout) :: errors
      logical, intent(inout) :: ok
      integer :: il
      if (.not. ok) return
      il = next_line(t)
      if (il == 0) then
         call errors%add('E-GMSH', 'truncated file: $End'//section//' is missing', file=t%path, &
                         line=t%nlines)
         ok = .false.
      else if (trim(adjustl(get_line(t, il))) /= '$End'//section) then
         call errors%add('E-GMSH', '$'//section//': expected $End'//section// &
                         ' after the declared number of entries, found "'// &
                         short(trim(get_line(t, il)))//'"', file=t%path, line=il)
         ok = .false.
      end if
   end subroutine expect_end

   !> Skip a section that Kontakt2D does not use.
   subroutine skip_section(t, section, errors, ok)
      type(msh_text_t), intent(inout) :: t
      character(len=*), intent(in) :: section
      type(error_list_t), intent(inout) :: errors
      logical, intent(out) :: ok
      integer :: il, il0
      il0 = t%pos
      ok = .true.
      do
         il = next_line(t)
         if (il == 0) then
            call errors%add('E-GMSH', 'truncated file: section $'//section//' has no $End'// &
                            section, file=t%path, line=il0)
            ok = .false.
            return
         end if
         if (trim(adjustl(get_line(t, il))) == '$End'//section) return
      end do
   end subroutine skip_section

end module gmsh_text
