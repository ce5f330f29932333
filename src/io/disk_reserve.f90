!> Room on the disk kept for closing a result file cleanly: a reserve file
!! whose blocks are allocated by the file system, and a probe that checks
!! that the disk can take a given number of bytes more before they are
!! written.
!!
!! Why not Fortran I/O.  gfortran reports no error when a write, a flush or
!! a close of a file on a full disk fails (measured with gfortran 12 on a
!! tmpfs: 6.5 MB written to a 1 MB file system, every iostat 0), and the
!! unit's file descriptor stays open, so that deleting the file frees
!! nothing.  The reserve therefore goes through the C library: `creat`,
!! `posix_fallocate` (allocates the blocks without writing them, or fails
!! with ENOSPC; glibc emulates it by writing where the file system cannot),
!! `ftruncate`, `close`, `unlink` (POSIX.1-2008).  A probe of n bytes
!! allocates reserve + n and truncates back to the reserve: no data are
!! written either way.
!!
!! Ref: POSIX.1-2008, posix_fallocate(), ftruncate(), creat(), unlink().
module disk_reserve
   use, intrinsic :: iso_c_binding, only: c_int, c_long, c_char, c_null_char
   use kinds, only: i8
   implicit none
   private
   public :: reserve_t

   !> A reserve file while it is held.
   type :: reserve_t
      private
      integer(c_int) :: fd = -1
      character(len=:), allocatable :: path
      integer(i8) :: nbytes = 0
   contains
      procedure :: hold => reserve_hold
      procedure :: probe => reserve_probe
      procedure :: release => reserve_release
      procedure :: held => reserve_held
   end type reserve_t

   interface
      function c_creat(path, mode) bind(c, name='creat') result(fd)
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int), value :: mode
         integer(c_int) :: fd
      end function c_creat
      function c_posix_fallocate(fd, offset, length) bind(c, name='posix_fallocate') result(e)
         import :: c_int, c_long
         integer(c_int), value :: fd
         integer(c_long), value :: offset, length
         integer(c_int) :: e
      end function c_posix_fallocate
      function c_ftruncate(fd, length) bind(c, name='ftruncate') result(e)
         import :: c_int, c_long
         integer(c_int), value :: fd
         integer(c_long), value :: length
         integer(c_int) :: e
      end function c_ftruncate
      function c_close(fd) bind(c, name='close') result(e)
         import :: c_int
         integer(c_int), value :: fd
         integer(c_int) :: e
      end function c_close
      function c_unlink(path) bind(c, name='unlink') result(e)
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int) :: e
      end function c_unlink
   end interface

contains

   !> Create `path` (replacing a file of that name) with `nbytes` allocated;
   !! err = 0 when held, else nothing is left behind.
   subroutine reserve_hold(this, path, nbytes, err)
      class(reserve_t), intent(inout) :: this
      character(len=*), intent(in) :: path
      integer(i8), intent(in) :: nbytes
      integer, intent(out) :: err
      call this%release()
      this%fd = c_creat(path//c_null_char, int(o'644', c_int))
      if (this%fd < 0) then
         err = -1
         return
      end if
      this%path = path
      this%nbytes = nbytes
      err = c_posix_fallocate(this%fd, 0_c_long, int(nbytes, c_long))
      if (err /= 0) call this%release()
   end subroutine reserve_hold

   !> Can the disk take `nbytes` more?  err = 0 when it can (the reserve is
   !! still held at its size); otherwise err /= 0 and the reserve is released,
   !! so that what is written next (the failure's status) finds its room.
   !! Without a reserve there is nothing to probe with: err = 0.
   subroutine reserve_probe(this, nbytes, err)
      class(reserve_t), intent(inout) :: this
      integer(i8), intent(in) :: nbytes
      integer, intent(out) :: err
      err = 0
      if (this%fd < 0) return
      err = c_posix_fallocate(this%fd, 0_c_long, int(this%nbytes + nbytes, c_long))
      if (err == 0) err = c_ftruncate(this%fd, int(this%nbytes, c_long))
      if (err /= 0) call this%release()
   end subroutine reserve_probe

   !> Delete the reserve file, if it is held.
   subroutine reserve_release(this)
      class(reserve_t), intent(inout) :: this
      integer(c_int) :: e
      if (this%fd < 0) return
      e = c_close(this%fd)
      e = c_unlink(this%path//c_null_char)
      this%fd = -1
   end subroutine reserve_release

   !> Is the reserve held?
   pure logical function reserve_held(this) result(yes)
      class(reserve_t), intent(in) :: this
      yes = this%fd >= 0
   end function reserve_held
end module disk_reserve
