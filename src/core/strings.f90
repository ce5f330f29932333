!> Small string helpers used by the reader, the listing and the messages.
module strings
   use kinds, only: dp
   implicit none
   private
   public :: upper, lower, same_name, itoa, rtoa, basename, strip_extension

contains

   !> True if two names are equal apart from case and trailing blanks.
   pure logical function same_name(a, b)
      character(len=*), intent(in) :: a, b
      same_name = upper(trim(a)) == upper(trim(b))
   end function same_name

   !> Upper-case copy of a string.
   pure function upper(s) result(r)
      character(len=*), intent(in) :: s
      character(len=len(s)) :: r
      integer :: i, c
      r = s
      do i = 1, len(s)
         c = iachar(s(i:i))
         if (c >= iachar('a') .and. c <= iachar('z')) r(i:i) = achar(c - 32)
      end do
   end function upper

   !> Lower-case copy of a string.
   pure function lower(s) result(r)
      character(len=*), intent(in) :: s
      character(len=len(s)) :: r
      integer :: i, c
      r = s
      do i = 1, len(s)
         c = iachar(s(i:i))
         if (c >= iachar('A') .and. c <= iachar('Z')) r(i:i) = achar(c + 32)
      end do
   end function lower

   !> Integer as text without blanks.
   pure function itoa(i) result(s)
      integer, intent(in) :: i
      character(len=:), allocatable :: s
      character(len=24) :: b
      write (b, '(i0)') i
      s = trim(b)
   end function itoa

   !> Real as short text (blanks removed), by default in E-notation with six
   !! significant digits: 1.50000E+00, -2.50000E-03, 1.00000E+100.
   !! (Plain ES12.5 would drop the letter E of a three-digit exponent and
   !! print 1.00000+100, which is not a number in a deck.)
   pure function rtoa(x, fmt) result(s)
      real(dp), intent(in) :: x
      character(len=*), intent(in), optional :: fmt  !! Fortran edit descriptor, default ES with E
      character(len=:), allocatable :: s
      character(len=40) :: b
      integer :: n
      if (present(fmt)) then
         write (b, fmt) x
         s = trim(adjustl(b))
      else
         write (b, '(es14.5e3)') x
         s = trim(adjustl(b))
         ! two exponent digits when they suffice: E+005 -> E+05
         n = len(s)
         if (n >= 5) then
            if (s(n - 4:n - 4) == 'E' .and. s(n - 2:n - 2) == '0') s = s(1:n - 3)//s(n - 1:n)
         end if
      end if
   end function rtoa

   !> Last path component.
   pure function basename(path) result(s)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: s
      integer :: k
      k = index(path, '/', back=.true.)
      s = path(k + 1:)
   end function basename

   !> Path without its last extension (only in the last component).
   pure function strip_extension(path) result(s)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: s
      integer :: k, kslash
      k = index(path, '.', back=.true.)
      kslash = index(path, '/', back=.true.)
      if (k > kslash + 1) then
         s = path(1:k - 1)
      else
         s = path
      end if
   end function strip_extension
end module strings
