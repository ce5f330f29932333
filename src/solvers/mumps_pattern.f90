!> The sparsity pattern given to MUMPS, as plain arrays (no MUMPS here): the upper triangle
!! of a symmetric matrix (i <= j, diagonal included) in column order, column j holding
!! entries cp(j-1)+1 : cp(j), rows sorted ascending, the diagonal last (MUMPS's centralized
!! assembled format, IRN and JCN); built once from the CSR equation graph by `upper_pattern`,
!! searched by `locate_entry`; and the graph of its couplings between the equations that are
!! not Schur variables (`reduced_graph`, what METIS orders).
module mumps_pattern
   use kinds, only: i8
   use errors, only: status_t, STAT_SOLVER
   use strings, only: itoa
   use sorting, only: insertion_sort
   implicit none
   private
   public :: upper_pattern, column_indices, locate_entry, reduced_graph

contains

   !> Upper-triangle pattern (column pointers, sorted rows, diagonal last)
   !! of a CSR equation graph; checks the graph.
   subroutine upper_pattern(neq, xadj, adjncy, cp, rows, status)
      integer, intent(in) :: neq, xadj(:), adjncy(:)
      integer, allocatable, intent(out) :: cp(:)     !! (0:neq) column pointers
      integer, allocatable, intent(out) :: rows(:)   !! (cp(neq)) rows of each column
      type(status_t), intent(inout) :: status
      integer, allocatable :: cnt(:), pos(:)
      integer :: r, c, p, j, k, q, last, ierr
      integer(i8) :: nnz8

      if (neq < 0) then
         call status%set(STAT_SOLVER, 'mumps solver: negative number of equations '//itoa(neq))
         return
      end if
      if (neq > 0) then
         if (size(xadj) < neq + 1) then
            call status%set(STAT_SOLVER, 'mumps solver: invalid equation graph (xadj has '// &
               itoa(size(xadj))//' entries, needs '//itoa(neq + 1)//')')
            return
         end if
         if (xadj(1) /= 1 .or. xadj(neq + 1) - 1 > size(adjncy)) then
            call status%set(STAT_SOLVER, &
               'mumps solver: invalid equation graph (xadj must start at 1 and end within adjncy)' &
               )
            return
         end if
      end if
      allocate (cnt(max(neq, 1)))
      cnt = 1
      do r = 1, neq
         if (xadj(r + 1) < xadj(r)) then
            call status%set(STAT_SOLVER, &
               'mumps solver: invalid equation graph (xadj decreases at row '//itoa(r)//')')
            return
         end if
         do p = xadj(r), xadj(r + 1) - 1
            c = adjncy(p)
            if (c < 1 .or. c > neq) then
               call status%set(STAT_SOLVER, 'mumps solver: invalid equation graph (row '// &
                  itoa(r)//' lists equation '//itoa(c)//')')
               return
            end if
            if (c /= r) cnt(max(r, c)) = cnt(max(r, c)) + 1
         end do
      end do
      nnz8 = sum(int(cnt(1:neq), i8))
      if (nnz8 >= int(huge(1), i8)) then
         call status%set(STAT_SOLVER, 'mumps solver: '//itoa(neq)// &
            ' equations give more than 2^31 matrix entries')
         return
      end if
      allocate (cp(0:neq), pos(max(neq, 1)), stat=ierr)
      if (ierr == 0) allocate (rows(nnz8), stat=ierr)
      if (ierr /= 0) then
         call status%set(STAT_SOLVER, 'mumps solver: cannot allocate a pattern of '// &
            itoa(int(nnz8))//' entries')
         return
      end if
      cp(0) = 0
      do j = 1, neq
         cp(j) = cp(j - 1) + cnt(j)
         pos(j) = cp(j - 1) + 1
      end do
      do r = 1, neq
         do p = xadj(r), xadj(r + 1) - 1
            c = adjncy(p)
            if (c == r) cycle
            j = max(r, c)
            rows(pos(j)) = min(r, c)
            pos(j) = pos(j) + 1
         end do
      end do
      do j = 1, neq
         rows(pos(j)) = j             ! the diagonal, the largest row of its column
      end do
      ! sort every column and drop duplicates (a coupling listed twice)
      q = 0
      last = 0
      do j = 1, neq
         k = cp(j - 1) + 1
         call insertion_sort(rows(k:cp(j)))
         do p = k, cp(j)
            if (p > k) then
               if (rows(p) == rows(p - 1)) cycle
            end if
            q = q + 1
            rows(q) = rows(p)
         end do
         cp(j - 1) = last
         last = q
      end do
      cp(neq) = q
      if (q < size(rows)) rows = rows(1:q)
   end subroutine upper_pattern

   !> Column index of every entry from the column pointers.
   pure subroutine column_indices(cp, jcn)
      integer, intent(in) :: cp(0:)
      integer, intent(out) :: jcn(:)
      integer :: j
      do j = 1, ubound(cp, 1)
         jcn(cp(j - 1) + 1:cp(j)) = j
      end do
   end subroutine column_indices

   !> Position of entry (i, j), i <= j, in the pattern's rows (IRN/JCN/A); 0 if the pattern
   !! does not hold it.  Binary search of column j's sorted rows.
   pure integer function locate_entry(cp, rows, i, j) result(p)
      integer, intent(in) :: cp(0:)     !! (0:neq) column pointers
      integer, intent(in) :: rows(:)    !! rows of each column, sorted
      integer, intent(in) :: i, j
      integer :: lo, hi, mid
      lo = cp(j - 1) + 1
      hi = cp(j)
      p = 0
      do while (lo <= hi)
         mid = (lo + hi)/2
         if (rows(mid) == i) then
            p = mid
            return
         else if (rows(mid) < i) then
            lo = mid + 1
         else
            hi = mid - 1
         end if
      end do
   end function locate_entry

   !> The graph of the pattern's couplings between the equations not listed in `skip`, both
   !! ends, no diagonal, as 1-based CSR (METIS's input): vertex sub(i) is equation i, numbered
   !! in equation order; sub(i) = 0 for a skipped equation.  adjncy has at least one entry.
   pure subroutine reduced_graph(cp, rows, skip, sub, xadj, adjncy)
      integer, intent(in) :: cp(0:)                    !! (0:n) column pointers
      integer, intent(in) :: rows(:)                   !! rows of each column
      integer, intent(in) :: skip(:)                   !! equations left out (Schur variables)
      integer, allocatable, intent(out) :: sub(:)      !! (n) vertex of each equation, or 0
      integer, allocatable, intent(out) :: xadj(:)     !! (nsub+1) row pointers
      integer, allocatable, intent(out) :: adjncy(:)   !! neighbours of each vertex
      integer, allocatable :: place(:)
      integer :: n, nsub, i, j, p, k
      n = ubound(cp, 1)
      allocate (sub(n))
      sub = 1
      if (size(skip) > 0) sub(skip) = 0
      nsub = 0
      do i = 1, n
         if (sub(i) > 0) then
            nsub = nsub + 1
            sub(i) = nsub
         end if
      end do
      allocate (xadj(nsub + 1))
      xadj = 0
      do j = 1, n
         if (sub(j) == 0) cycle
         do p = cp(j - 1) + 1, cp(j)
            i = rows(p)
            if (i == j .or. sub(i) == 0) cycle
            xadj(sub(i) + 1) = xadj(sub(i) + 1) + 1
            xadj(sub(j) + 1) = xadj(sub(j) + 1) + 1
         end do
      end do
      xadj(1) = 1
      do k = 1, nsub
         xadj(k + 1) = xadj(k + 1) + xadj(k)
      end do
      allocate (adjncy(max(xadj(nsub + 1) - 1, 1)), place(nsub + 1))
      place(1:nsub) = xadj(1:nsub)
      do j = 1, n
         if (sub(j) == 0) cycle
         do p = cp(j - 1) + 1, cp(j)
            i = rows(p)
            if (i == j .or. sub(i) == 0) cycle
            adjncy(place(sub(i))) = sub(j)
            place(sub(i)) = place(sub(i)) + 1
            adjncy(place(sub(j))) = sub(i)
            place(sub(j)) = place(sub(j)) + 1
         end do
      end do
   end subroutine reduced_graph
end module mumps_pattern
