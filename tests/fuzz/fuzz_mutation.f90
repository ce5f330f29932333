!> The mutation engine of the in-process fuzzer (tests/fuzz/fuzz_readers.f90):
!! a reproducible random stream (xorshift64) and mutations of a deck or a
!! gmsh file held as one string.
!!
!! The operators know the shape of the input, not its meaning: bytes (any
!! value, printable ones more often), fixed-width fields replaced by
!! "interesting" values (0, -1, the largest I5 and default integers, 1e308,
!! nan, inf, text, blanks), whitespace-separated tokens of a .msh, whole
!! lines (deleted, duplicated, duplicated thousands of times, swapped,
!! replaced by a block or sub-block keyword, spliced from another input) and
!! truncation.  Several are applied to one input.
!!
!! Ref: M. Zalewski, american fuzzy lop, "technical details" (the deterministic
!! and havoc stages these operators are modelled on); G. Marsaglia,
!! "Xorshift RNGs", J. Stat. Software 8 (14), 2003 (xorshift64, shifts 12, 25, 27).
module fuzz_mutation
   use, intrinsic :: iso_fortran_env, only: int64
   implicit none
   private
   public :: rng_t, mutate

   !> xorshift64: 64 bits of state, a reproducible stream per seed.
   type :: rng_t
      integer(int64) :: s = 88172645463325252_int64
   contains
      procedure :: seed => rng_seed
      procedure :: below => rng_below
   end type rng_t

   character(len=12), parameter :: tokens(30) = [character(len=12) :: '0', '-1', '1', '2', '99999', '-9999', &
                                                 '2147483647', '-2147483648', '99999999999', '1e308', '-1e308', &
                                                 '1e-308', '1e999', 'nan', 'inf', '-inf', '0.0', '1e38', '-0.0', 'abc', &
                                                 ' ', '     ', 'GROUP', 'A', 'B', '11', '10', '01', '1.5', '0.49999']
   character(len=18), parameter :: keywords(48) = [character(len=18) :: 'TITLE', 'CONTROL', 'OPTIONS', 'MESH', &
                                                   'ELEMENTS', 'NODES', 'RESTRAINTS', 'TIES', 'MATERIALS', 'LOADS', &
                                                   'CONTACT', 'INCREMENTS', 'END', 'POINT', 'EDGE', 'BODY', &
                                                   'GROUP     left', 'INTERFACE', 'NORMAL', 'TANGENT', 'FRICTION', &
                                                   'SURFACE   A', 'SURFACE   B', 'PAIRS', 'MATCHING', 'RIGID', &
                                                   'START', 'UNITS', 'LAW', 'HARDENING', 'SLIP', 'TOLERANCE', &
                                                   'UPDATE', 'CONVERGE', 'AUGMENTED', 'REPEATS', 'GMSH', 'MATERIAL', &
                                                   '$MeshFormat', '$EndMeshFormat', '$Nodes', '$EndNodes', &
                                                   '$Elements', '$EndElements', '$PhysicalNames', '$Entities', &
                                                   '$EndEntities', '$EndPhysicalNames']

contains

   subroutine rng_seed(this, seed)
      class(rng_t), intent(inout) :: this
      integer(int64), intent(in) :: seed
      integer :: k
      integer(int64) :: dummy
      this%s = ieor(seed, 88172645463325252_int64)
      if (this%s == 0) this%s = 1
      do k = 1, 8
         dummy = this%below(2)
      end do
   end subroutine rng_seed

   !> A uniform integer in 0..n-1 (n >= 1).
   integer function rng_below(this, n) result(r)
      class(rng_t), intent(inout) :: this
      integer, intent(in) :: n
      integer(int64) :: x
      this%s = ieor(this%s, shiftr(this%s, 12))
      this%s = ieor(this%s, shiftl(this%s, 25))
      this%s = ieor(this%s, shiftr(this%s, 27))
      ! no multiplication (xorshift64*'s would overflow a signed integer: UBSan reports it)
      x = this%s
      r = int(modulo(shiftr(x, 16), int(max(n, 1), int64)))
   end function rng_below

   !> Apply 1 to 4 mutations to text; other is another input of the corpus
   !! (for splicing); msh selects the token operators of a .msh file.
   subroutine mutate(rng, text, other, msh)
      type(rng_t), intent(inout) :: rng
      character(len=:), allocatable, intent(inout) :: text
      character(len=*), intent(in) :: other
      logical, intent(in) :: msh
      integer :: k, nmut
      nmut = 1 + rng%below(4)
      do k = 1, nmut
         select case (rng%below(12))
         case (0)
            call set_byte(rng, text)
         case (1)
            call insert_bytes(rng, text)
         case (2)
            call delete_bytes(rng, text)
         case (3, 4)
            if (msh) then
               call replace_token(rng, text)
            else
               call replace_field(rng, text)
            end if
         case (5)
            call line_op(rng, text, 'delete', '')
         case (6)
            call line_op(rng, text, 'duplicate', '')
         case (7)
            call line_op(rng, text, 'swap', '')
         case (8)
            call line_op(rng, text, 'keyword', '')
         case (9)
            call line_op(rng, text, 'splice', other)
         case (10)
            if (rng%below(8) == 0) then
               call line_op(rng, text, 'repeat', '')
            else if (msh) then
               call replace_token(rng, text)
            else
               call replace_field(rng, text)
            end if
         case default
            if (rng%below(4) == 0) then
               text = text(1:rng%below(len(text) + 1))
            else
               call replace_field(rng, text)
            end if
         end select
      end do
   end subroutine mutate

   !> One byte set to a random value (printable three times in four).
   subroutine set_byte(rng, text)
      type(rng_t), intent(inout) :: rng
      character(len=:), allocatable, intent(inout) :: text
      integer :: p
      if (len(text) == 0) return
      p = 1 + rng%below(len(text))
      text(p:p) = random_byte(rng)
   end subroutine set_byte

   function random_byte(rng) result(c)
      type(rng_t), intent(inout) :: rng
      character(len=1) :: c
      select case (rng%below(8))
      case (0)
         c = achar(rng%below(256))
      case (1)
         c = achar(9)
      case (2)
         c = ' '
      case default
         c = achar(32 + rng%below(95))
      end select
   end function random_byte

   subroutine insert_bytes(rng, text)
      type(rng_t), intent(inout) :: rng
      character(len=:), allocatable, intent(inout) :: text
      integer :: p, n, k
      character(len=:), allocatable :: ins
      p = rng%below(len(text) + 1)
      n = 1 + rng%below(8)
      allocate (character(len=n) :: ins)
      do k = 1, n
         ins(k:k) = random_byte(rng)
      end do
      text = text(1:p)//ins//text(p + 1:)
   end subroutine insert_bytes

   subroutine delete_bytes(rng, text)
      type(rng_t), intent(inout) :: rng
      character(len=:), allocatable, intent(inout) :: text
      integer :: p, n
      if (len(text) == 0) return
      p = 1 + rng%below(len(text))
      n = 1 + rng%below(16)
      text = text(1:p - 1)//text(min(p + n, len(text) + 1):)
   end subroutine delete_bytes

   !> A fixed-width field (5 or 10 columns at a multiple of 5) of a random line
   !! replaced by an interesting token, right-justified.
   subroutine replace_field(rng, text)
      type(rng_t), intent(inout) :: rng
      character(len=:), allocatable, intent(inout) :: text
      integer :: l1, l2, c1, w
      character(len=:), allocatable :: line, tok
      call random_line(rng, text, l1, l2)
      if (l1 == 0) return
      line = text(l1:l2)
      w = merge(5, 10, rng%below(2) == 0)
      c1 = 1 + 5*rng%below(9)
      if (len(line) < c1 + w - 1) line = line//repeat(' ', c1 + w - 1 - len(line))
      tok = trim(tokens(1 + rng%below(size(tokens))))
      if (len(tok) > w) tok = tok(1:w)
      line(c1:c1 + w - 1) = repeat(' ', w - len(tok))//tok
      text = text(1:l1 - 1)//line//text(l2 + 1:)
   end subroutine replace_field

   !> A blank-separated token of a random line replaced by an interesting token.
   subroutine replace_token(rng, text)
      type(rng_t), intent(inout) :: rng
      character(len=:), allocatable, intent(inout) :: text
      integer :: l1, l2, i, ntok, want, t1, t2
      logical :: inword
      call random_line(rng, text, l1, l2)
      if (l1 == 0 .or. l2 < l1) return
      ntok = 0
      inword = .false.
      do i = l1, l2
         if (text(i:i) /= ' ') then
            if (.not. inword) ntok = ntok + 1
            inword = .true.
         else
            inword = .false.
         end if
      end do
      if (ntok == 0) return
      want = 1 + rng%below(ntok)
      ntok = 0
      inword = .false.
      t1 = 0
      t2 = l2
      do i = l1, l2
         if (text(i:i) /= ' ') then
            if (.not. inword) then
               ntok = ntok + 1
               if (ntok == want) t1 = i
            end if
            inword = .true.
         else
            if (inword .and. ntok == want) then
               t2 = i - 1
               exit
            end if
            inword = .false.
         end if
      end do
      if (t1 == 0) return
      text = text(1:t1 - 1)//trim(tokens(1 + rng%below(size(tokens))))//text(t2 + 1:)
   end subroutine replace_token

   !> Line operations: delete, duplicate, swap with another, replace by a
   !! keyword, splice a line of `other`, repeat 1000 to 5000 times.
   subroutine line_op(rng, text, op, other)
      type(rng_t), intent(inout) :: rng
      character(len=:), allocatable, intent(inout) :: text
      character(len=*), intent(in) :: op, other
      integer :: l1, l2, m1, m2, n
      character(len=:), allocatable :: a, b, tmp
      call random_line(rng, text, l1, l2)
      if (l1 == 0) return
      select case (op)
      case ('delete')
         text = text(1:l1 - 1)//text(min(l2 + 2, len(text) + 1):)
      case ('duplicate')
         text = text(1:l2)//achar(10)//text(l1:)
      case ('repeat')
         n = 1000 + rng%below(4001)
         a = text(l1:l2)//achar(10)
         text = text(1:l1 - 1)//repeat(a, n)//text(l1:)
      case ('swap')
         call random_line(rng, text, m1, m2)
         if (m1 == 0 .or. m1 == l1) return
         if (m1 < l1) then
            tmp = text(1:m1 - 1)
            a = text(m1:m2)
            b = text(l1:l2)
            text = tmp//b//text(m2 + 1:l1 - 1)//a//text(l2 + 1:)
         else
            a = text(l1:l2)
            b = text(m1:m2)
            text = text(1:l1 - 1)//b//text(l2 + 1:m1 - 1)//a//text(m2 + 1:)
         end if
      case ('keyword')
         text = text(1:l1 - 1)//trim(keywords(1 + rng%below(size(keywords))))//text(l2 + 1:)
      case ('splice')
         if (len(other) == 0) return
         call random_line(rng, other, m1, m2)
         if (m1 == 0) return
         text = text(1:l1 - 1)//other(m1:m2)//text(l2 + 1:)
      end select
   end subroutine line_op

   !> Bounds l1..l2 of a random line of text (without its newline); l1 = 0 if none.
   subroutine random_line(rng, text, l1, l2)
      type(rng_t), intent(inout) :: rng
      character(len=*), intent(in) :: text
      integer, intent(out) :: l1, l2
      integer :: p
      l1 = 0
      l2 = 0
      if (len(text) == 0) return
      p = 1 + rng%below(len(text))
      l1 = index(text(1:p), achar(10), back=.true.) + 1
      l2 = index(text(p:), achar(10))
      if (l2 == 0) then
         l2 = len(text)
      else
         l2 = p + l2 - 2
      end if
      if (l2 < l1 - 1) l2 = l1 - 1
   end subroutine random_line

end module fuzz_mutation
