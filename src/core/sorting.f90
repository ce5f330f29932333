!> Insertion sort of short lists (the adjacency of a node, the rows of a
!! matrix column, the break points of an edge): a few to a few dozen
!! entries, where it beats anything cleverer.
module sorting
   use kinds, only: dp
   implicit none
   private
   public :: insertion_sort

   !> Sort an integer or real(dp) array in place, ascending.
   interface insertion_sort
      module procedure sort_integers, sort_reals
   end interface insertion_sort

contains

   pure subroutine sort_integers(a)
      integer, intent(inout) :: a(:)
      integer :: i, j, v
      do i = 2, size(a)
         v = a(i)
         j = i - 1
         do while (j >= 1)
            if (a(j) <= v) exit
            a(j + 1) = a(j)
            j = j - 1
         end do
         a(j + 1) = v
      end do
   end subroutine sort_integers

   pure subroutine sort_reals(a)
      real(dp), intent(inout) :: a(:)
      integer :: i, j
      real(dp) :: v
      do i = 2, size(a)
         v = a(i)
         j = i - 1
         do while (j >= 1)
            if (a(j) <= v) exit
            a(j + 1) = a(j)
            j = j - 1
         end do
         a(j + 1) = v
      end do
   end subroutine sort_reals
end module sorting
