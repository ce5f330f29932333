!> In-process fuzzer of the input readers: mutated decks and .msh files fed
!! to `read_model` (deck reader, gmsh reader, contact definition, model
!! checks) in one process, many inputs per second.
!!
!!     fuzz_readers CORPUS WORKDIR SEED RUNS [FINDINGS]
!!     fuzz_readers CORPUS WORKDIR SEED RUNS --emit
!!
!! The second form only writes the mutated inputs, run i into the existing
!! folder WORKDIR/i/ (fuzz.dat and the mesh), for the whole-process mode of
!! tools/fuzz.py: one mutation engine for both modes.
!!
!! CORPUS lists one input per line: a deck, and after a blank the .msh file
!! its MESH block names (relative to the deck, as the deck names it).  Every
!! run picks an input, mutates the deck or the mesh (tests/fuzz/fuzz_mutation),
!! writes them to WORKDIR (fuzz.dat and the mesh's name) and reads them.  A
!! crash leaves the input that caused it there.  The contract checked after
!! every read:
!!
!! * every input error names a line of a file (`file:line`), and its message
!!   and echoed card are printable ASCII of bounded length;
!! * a model read without errors holds only finite numbers;
!! * no read takes longer than 2 s (a "slow" input: quadratic work).
!!
!! A violation is counted and its input copied to FINDINGS (when given), in
!! the folder <kind>_<seed>_<run> (fuzz.dat and the mesh).  The last line printed is the summary
!! `runs=... errors=... accepted=... no_location=... bad_text=... nonfinite=...
!! slow=... max_seconds=...`; the exit code is 0, or 1 with any violation.
program fuzz_readers
   use, intrinsic :: iso_fortran_env, only: int64, output_unit
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use kinds, only: dp
   use errors, only: error_list_t
   use model, only: model_t
   use model_input, only: read_model
   use fuzz_mutation, only: rng_t, mutate
   implicit none

   type :: input_t
      character(len=:), allocatable :: deck, msh, msh_name
   end type input_t

   type(input_t), allocatable :: corpus(:)
   character(len=:), allocatable :: work, findings, deck, msh, kind_found
   character(len=4096) :: arg
   integer(int64) :: seed, t0, t1, rate
   integer :: runs, irun, k, nin, nbad(4), naccepted, nerrors, both
   real(dp) :: secs, max_secs
   type(rng_t) :: rng
   type(model_t) :: m
   type(error_list_t) :: errs, warns
   logical :: mutate_msh, emit

   if (command_argument_count() < 4) then
      write (output_unit, '(a)') 'usage: fuzz_readers CORPUS WORKDIR SEED RUNS [FINDINGS]'
      error stop 2
   end if
   call get_command_argument(1, arg)
   call read_corpus(trim(arg), corpus)
   call get_command_argument(2, arg)
   work = trim(arg)
   call get_command_argument(3, arg)
   read (arg, *) seed
   call get_command_argument(4, arg)
   read (arg, *) runs
   findings = ''
   emit = .false.
   if (command_argument_count() >= 5) then
      call get_command_argument(5, arg)
      findings = trim(arg)
      emit = findings == '--emit'
   end if
   nin = size(corpus)
   if (nin == 0) error stop 'fuzz_readers: empty corpus'
   call rng%seed(seed)
   nbad = 0
   naccepted = 0
   nerrors = 0
   max_secs = 0.0_dp
   call system_clock(count_rate=rate)
   do irun = 1, runs
      k = 1 + rng%below(nin)
      deck = corpus(k)%deck
      msh = corpus(k)%msh
      mutate_msh = rng%below(2) == 0
      mutate_msh = mutate_msh .and. len(msh) > 0
      if (mutate_msh) then
         call mutate(rng, msh, corpus(1 + rng%below(nin))%msh, .true.)
         both = rng%below(4)
         if (both == 0) call mutate(rng, deck, corpus(1 + rng%below(nin))%deck, .false.)
      else
         call mutate(rng, deck, corpus(1 + rng%below(nin))%deck, .false.)
      end if
      if (emit) then
         write (arg, '(i0)') irun    ! the folder exists (tools/fuzz.py makes it)
         call put(work//'/'//trim(arg)//'/fuzz.dat', deck)
         if (len(corpus(k)%msh_name) > 0) call put(work//'/'//trim(arg)//'/'//corpus(k)%msh_name, msh)
         cycle
      end if
      call put(work//'/fuzz.dat', deck)
      if (len(corpus(k)%msh_name) > 0) call put(work//'/'//corpus(k)%msh_name, msh)
      call system_clock(t0)
      call read_model(work//'/fuzz.dat', m, errs, warns)
      call system_clock(t1)
      secs = real(t1 - t0, dp)/real(rate, dp)
      max_secs = max(max_secs, secs)
      kind_found = ''
      if (errs%n > 0) then
         nerrors = nerrors + 1
         call check_errors(errs, kind_found)
      else
         naccepted = naccepted + 1
         if (.not. model_finite(m)) kind_found = 'nonfinite'
      end if
      if (len(kind_found) == 0 .and. secs > 2.0_dp) kind_found = 'slow'
      if (len(kind_found) > 0) then
         select case (kind_found)
         case ('no_location')
            nbad(1) = nbad(1) + 1
         case ('bad_text')
            nbad(2) = nbad(2) + 1
         case ('nonfinite')
            nbad(3) = nbad(3) + 1
         case ('slow')
            nbad(4) = nbad(4) + 1
         end select
         if (len(findings) > 0) call keep(kind_found, irun, deck, msh, corpus(k)%msh_name)
      end if
   end do
   if (emit) stop
   write (output_unit, '(a,i0,a,i0,a,i0,a,i0,a,i0,a,i0,a,i0,a,f0.3)') 'runs=', runs, ' errors=', nerrors, &
      ' accepted=', naccepted, ' no_location=', nbad(1), ' bad_text=', nbad(2), ' nonfinite=', nbad(3), &
      ' slow=', nbad(4), ' max_seconds=', max_secs
   if (sum(nbad) > 0) stop 1

contains

   !> Every error names a file and a line; messages and cards are printable
   !! ASCII, at most 4096 characters (cards are echoed cut).
   subroutine check_errors(errs, kind_found)
      type(error_list_t), intent(in) :: errs
      character(len=:), allocatable, intent(inout) :: kind_found
      integer :: i
      do i = 1, errs%n
         associate (e => errs%items(i))
            if (e%line <= 0 .or. len(e%file) == 0) then
               kind_found = 'no_location'
               write (output_unit, '(a)') 'no location: '//printable(e%message)
               return
            end if
            if (.not. (is_printable(e%message) .and. is_printable(e%card)) .or. len(e%message) > 4096 .or. &
                len(e%card) > 4096) then
               kind_found = 'bad_text'
               write (output_unit, '(a)') 'bad text: '//printable(e%message(1:min(200, len(e%message))))
               return
            end if
         end associate
      end do
   end subroutine check_errors

   pure logical function is_printable(s)
      character(len=*), intent(in) :: s
      integer :: i
      is_printable = .true.
      do i = 1, len(s)
         if (iachar(s(i:i)) < 32 .or. iachar(s(i:i)) > 126) then
            is_printable = .false.
            return
         end if
      end do
   end function is_printable

   pure function printable(s) result(r)
      character(len=*), intent(in) :: s
      character(len=len(s)) :: r
      integer :: i
      r = s
      do i = 1, len(s)
         if (iachar(s(i:i)) < 32 .or. iachar(s(i:i)) > 126) r(i:i) = '?'
      end do
   end function printable

   !> Every real of an accepted model is finite.
   logical function model_finite(m) result(ok)
      type(model_t), intent(in) :: m
      integer :: k
      ok = .true.
      if (allocated(m%coord)) ok = ok .and. all(ieee_is_finite(m%coord))
      if (allocated(m%lambda)) ok = ok .and. all(ieee_is_finite(m%lambda))
      if (allocated(m%mats)) then
         do k = 1, size(m%mats)
            ok = ok .and. ieee_is_finite(m%mats(k)%young) .and. ieee_is_finite(m%mats(k)%poiss) .and. &
                 ieee_is_finite(m%mats(k)%thick)
         end do
      end if
      if (allocated(m%fixes)) then
         do k = 1, size(m%fixes)
            ok = ok .and. all(ieee_is_finite(m%fixes(k)%value))
         end do
      end if
      if (allocated(m%point_loads)) then
         do k = 1, size(m%point_loads)
            ok = ok .and. all(ieee_is_finite(m%point_loads(k)%force))
         end do
      end if
      if (allocated(m%edge_loads)) then
         do k = 1, size(m%edge_loads)
            ok = ok .and. all(ieee_is_finite(m%edge_loads(k)%pn)) .and. all(ieee_is_finite(m%edge_loads(k)%pt))
         end do
      end if
      if (allocated(m%body_loads)) then
         do k = 1, size(m%body_loads)
            ok = ok .and. all(ieee_is_finite(m%body_loads(k)%b))
         end do
      end if
      if (allocated(m%contact%ifaces)) then
         do k = 1, size(m%contact%ifaces)
            associate (f => m%contact%ifaces(k))
               ok = ok .and. ieee_is_finite(f%cn) .and. ieee_is_finite(f%cn2) .and. ieee_is_finite(f%m) .and. &
                    ieee_is_finite(f%m2)
               if (allocated(f%r_t)) ok = ok .and. all(ieee_is_finite(f%r_t))
            end associate
         end do
      end if
      if (allocated(m%contact%pairs)) then
         do k = 1, size(m%contact%pairs)
            associate (p => m%contact%pairs(k))
               ok = ok .and. ieee_is_finite(p%area) .and. ieee_is_finite(p%g0) .and. all(ieee_is_finite(p%n)) &
                    .and. all(ieee_is_finite(p%t)) .and. ieee_is_finite(p%estar)
            end associate
         end do
      end if
   end function model_finite

   !> The corpus: "deck [mesh-name]" per line; files read whole.
   subroutine read_corpus(path, corpus)
      character(len=*), intent(in) :: path
      type(input_t), allocatable, intent(out) :: corpus(:)
      character(len=4096) :: line
      character(len=:), allocatable :: dpath, mname
      integer :: u, ios, n, b, k
      open (newunit=u, file=path, status='old', action='read')
      n = 0
      do
         read (u, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (len_trim(line) > 0) n = n + 1
      end do
      rewind (u)
      allocate (corpus(n))
      k = 0
      do
         read (u, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (len_trim(line) == 0) cycle
         k = k + 1
         b = index(trim(line), ' ')
         if (b == 0) then
            dpath = trim(line)
            mname = ''
         else
            dpath = line(1:b - 1)
            mname = trim(adjustl(line(b + 1:)))
         end if
         corpus(k)%deck = slurp(dpath)
         corpus(k)%msh_name = mname
         corpus(k)%msh = ''
         if (len(mname) > 0) corpus(k)%msh = slurp(dpath(1:index(dpath, '/', back=.true.))//mname)
      end do
      close (u)
   end subroutine read_corpus

   function slurp(path) result(s)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: s
      integer :: u, n
      open (newunit=u, file=path, access='stream', form='unformatted', status='old', action='read')
      inquire (unit=u, size=n)
      allocate (character(len=n) :: s)
      if (n > 0) read (u) s
      close (u)
   end function slurp

   subroutine put(path, s)
      character(len=*), intent(in) :: path, s
      integer :: u
      open (newunit=u, file=path, access='stream', form='unformatted', status='replace', action='write')
      write (u) s
      close (u)
   end subroutine put

   !> Keep an input that broke the contract.
   subroutine keep(kind_found, irun, deck, msh, msh_name)
      character(len=*), intent(in) :: kind_found, deck, msh, msh_name
      integer, intent(in) :: irun
      character(len=64) :: tag
      write (tag, '(a,"_",i0,"_",i0)') kind_found, seed, irun
      call execute_command_line('mkdir -p "'//findings//'/'//trim(tag)//'"')
      call put(findings//'/'//trim(tag)//'/fuzz.dat', deck)
      if (len(msh_name) > 0) call put(findings//'/'//trim(tag)//'/'//msh_name, msh)
   end subroutine keep

end program fuzz_readers
