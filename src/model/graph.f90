!> Node and equation adjacency graphs (CSR), built from the element
!! connectivity plus extra node-node links (contact pairs, ties, rigid-body
!! reference nodes).  The solvers take the equation graph to size their
!! storage once; the renumbering takes the node graph.  The profile of an
!! equation graph (column tops, skyline length) is here too: the skyline
!! solver sizes its storage with it, and the equation numbering reports it
!! before and after renumbering without building a solver.
module graph
   use kinds, only: dp, i8
   use errors, only: status_t, STAT_SOLVER
   use model, only: model_t
   use dof_map, only: dof_map_t
   use sorting, only: insertion_sort
   implicit none
   private
   public :: build_node_graph, build_equation_graph, column_tops, graph_profile

contains

   !> Node graph: for every node the sorted list of nodes it shares an element
   !! or a link with (itself included).
   subroutine build_node_graph(m, links, xadj, adjncy)
      type(model_t), intent(in) :: m
      integer, intent(in) :: links(:, :)            !! (2, nlink)
      integer, allocatable, intent(out) :: xadj(:)  !! (npoin+1)
      integer, allocatable, intent(out) :: adjncy(:)
      integer, allocatable :: nel(:), elptr(:), ellist(:), lkptr(:), lklist(:), nlk(:), mark(:)
      integer :: ie, k, j, ip, jp, n, pos, kl

      ! node -> elements
      allocate (nel(m%npoin + 1), nlk(m%npoin + 1))
      nel = 0
      nlk = 0
      do ie = 1, m%nelem
         do k = 1, m%nnode_e(ie)
            nel(m%lnods(k, ie)) = nel(m%lnods(k, ie)) + 1
         end do
      end do
      do kl = 1, size(links, 2)
         nlk(links(1, kl)) = nlk(links(1, kl)) + 1
         nlk(links(2, kl)) = nlk(links(2, kl)) + 1
      end do
      call counts_to_ptr(nel, elptr)
      call counts_to_ptr(nlk, lkptr)
      allocate (ellist(elptr(m%npoin + 1) - 1), lklist(lkptr(m%npoin + 1) - 1))
      nel = 0
      do ie = 1, m%nelem
         do k = 1, m%nnode_e(ie)
            ip = m%lnods(k, ie)
            ellist(elptr(ip) + nel(ip)) = ie
            nel(ip) = nel(ip) + 1
         end do
      end do
      nlk = 0
      do kl = 1, size(links, 2)
         ip = links(1, kl)
         jp = links(2, kl)
         lklist(lkptr(ip) + nlk(ip)) = jp
         nlk(ip) = nlk(ip) + 1
         lklist(lkptr(jp) + nlk(jp)) = ip
         nlk(jp) = nlk(jp) + 1
      end do

      ! two passes: count, then fill
      allocate (mark(m%npoin), xadj(m%npoin + 1))
      mark = 0
      xadj(1) = 1
      do ip = 1, m%npoin
         n = 0
         call visit(ip, .false.)
         xadj(ip + 1) = xadj(ip) + n
      end do
      allocate (adjncy(xadj(m%npoin + 1) - 1))
      mark = 0
      do ip = 1, m%npoin
         n = 0
         pos = xadj(ip)
         call visit(ip, .true.)
         call insertion_sort(adjncy(xadj(ip):xadj(ip + 1) - 1))
      end do
   contains
      subroutine visit(node, fill)
         integer, intent(in) :: node
         logical, intent(in) :: fill
         call add(node, node, fill)
         do j = elptr(node), elptr(node + 1) - 1
            ie = ellist(j)
            do k = 1, m%nnode_e(ie)
               call add(node, m%lnods(k, ie), fill)
            end do
         end do
         do j = lkptr(node), lkptr(node + 1) - 1
            call add(node, lklist(j), fill)
         end do
      end subroutine visit
      subroutine add(node, q, fill)
         integer, intent(in) :: node, q
         logical, intent(in) :: fill
         if (mark(q) == node) return
         mark(q) = node
         if (fill) adjncy(pos + n) = q
         n = n + 1
      end subroutine add
   end subroutine build_node_graph

   !> Equation graph from the node graph: equations of adjacent nodes couple.
   subroutine build_equation_graph(map, nxadj, nadj, xadj, adjncy)
      type(dof_map_t), intent(in) :: map
      integer, intent(in) :: nxadj(:), nadj(:)       !! node graph
      integer, allocatable, intent(out) :: xadj(:)   !! (neq+1)
      integer, allocatable, intent(out) :: adjncy(:)
      integer, allocatable :: nodes_of_eq_ptr(:), nodes_of_eq(:), cnt(:), mark(:)
      integer :: ip, idof, ieq, j, k, jp, jdof, jeq, n, pass, pos

      ! equation -> nodes carrying it (more than one under ties)
      allocate (cnt(map%neq + 1))
      cnt = 0
      do ip = 1, map%npoin
         do idof = 1, 2
            ieq = map%id(idof, ip)
            if (ieq > 0) cnt(ieq) = cnt(ieq) + 1
         end do
      end do
      call counts_to_ptr(cnt, nodes_of_eq_ptr)
      allocate (nodes_of_eq(nodes_of_eq_ptr(map%neq + 1) - 1))
      cnt = 0
      do ip = 1, map%npoin
         do idof = 1, 2
            ieq = map%id(idof, ip)
            if (ieq > 0) then
               nodes_of_eq(nodes_of_eq_ptr(ieq) + cnt(ieq)) = ip
               cnt(ieq) = cnt(ieq) + 1
            end if
         end do
      end do

      allocate (xadj(map%neq + 1), mark(map%neq))
      allocate (adjncy(0))
      do pass = 1, 2
         mark = 0
         xadj(1) = 1
         do ieq = 1, map%neq
            n = 0
            pos = xadj(ieq)
            do k = nodes_of_eq_ptr(ieq), nodes_of_eq_ptr(ieq + 1) - 1
               ip = nodes_of_eq(k)
               do j = nxadj(ip), nxadj(ip + 1) - 1
                  jp = nadj(j)
                  do jdof = 1, 2
                     jeq = map%id(jdof, jp)
                     if (jeq <= 0) cycle
                     if (mark(jeq) == ieq) cycle
                     mark(jeq) = ieq
                     if (pass == 2) adjncy(pos + n) = jeq
                     n = n + 1
                  end do
               end do
            end do
            xadj(ieq + 1) = xadj(ieq) + n
            if (pass == 2) call insertion_sort(adjncy(xadj(ieq):xadj(ieq + 1) - 1))
         end do
         if (pass == 1) then
            deallocate (adjncy)
            allocate (adjncy(xadj(map%neq + 1) - 1))
         end if
      end do
   end subroutine build_equation_graph

   !> Turn counts(1:n) into 1-based pointers ptr(1:n+1).
   subroutine counts_to_ptr(counts, ptr)
      integer, intent(in) :: counts(:)
      integer, allocatable, intent(out) :: ptr(:)
      integer :: i, n
      n = size(counts) - 1
      allocate (ptr(n + 1))
      ptr(1) = 1
      do i = 1, n
         ptr(i + 1) = ptr(i) + counts(i)
      end do
   end subroutine counts_to_ptr
   !> Column tops of the profile from a CSR equation graph.
   !!
   !! For every coupling (r, c) listed in the graph, column max(r, c) must
   !! reach row min(r, c); the graph may list each coupling once or twice
   !! (one triangle or both).  O(neq + nnz) work.
   !! Ref: Bathe (1996), the COLSOL storage scheme (column heights, array MAXA).
   pure subroutine column_tops(neq, xadj, adjncy, top, ierr, msg)
      integer, intent(in) :: neq          !! number of equations
      integer, intent(in) :: xadj(:)      !! (neq+1) 1-based CSR row pointers
      integer, intent(in) :: adjncy(:)    !! coupled equations of each row
      integer, intent(out) :: top(:)      !! (neq) first coupled row of each column
      integer, intent(out) :: ierr        !! 0 on success
      character(len=:), allocatable, intent(out) :: msg  !! reason when ierr /= 0
      integer :: r, c, p, i, j
      character(len=80) :: buf

      ierr = 0
      msg = ''
      if (neq < 0) then
         ierr = 1
         write (buf, '(a,i0)') 'invalid equation graph: negative number of equations ', neq
         msg = trim(buf)
         return
      end if
      do j = 1, neq
         top(j) = j
      end do
      if (neq == 0) return
      if (size(xadj) < neq + 1) then
         ierr = 1
         write (buf, '(a,i0,a,i0)') 'invalid equation graph: xadj has ', size(xadj), &
            ' entries, needs ', neq + 1
         msg = trim(buf)
         return
      end if
      if (xadj(1) /= 1 .or. xadj(neq + 1) - 1 > size(adjncy)) then
         ierr = 1
         msg = 'invalid equation graph: xadj must start at 1 and end within adjncy'
         return
      end if
      do r = 1, neq
         if (xadj(r + 1) < xadj(r)) then
            ierr = 1
            write (buf, '(a,i0)') 'invalid equation graph: xadj decreases at row ', r
            msg = trim(buf)
            return
         end if
         do p = xadj(r), xadj(r + 1) - 1
            c = adjncy(p)
            if (c < 1 .or. c > neq) then
               ierr = 1
               write (buf, '(a,i0,a,i0)') 'invalid equation graph: row ', r, &
                  ' lists equation ', c
               msg = trim(buf)
               return
            end if
            i = min(r, c)
            j = max(r, c)
            if (i < top(j)) top(j) = i
         end do
      end do
   end subroutine column_tops

   !> Profile of an equation graph without building a solver.
   !!
   !! Meant for comparing numberings (before and after renumbering): the
   !! profile length is what the skyline solver would store.
   subroutine graph_profile(neq, xadj, adjncy, nprof, mean_height, max_height, status)
      integer, intent(in) :: neq              !! number of equations
      integer, intent(in) :: xadj(:)          !! (neq+1) 1-based CSR row pointers
      integer, intent(in) :: adjncy(:)        !! coupled equations of each row
      integer(i8), intent(out) :: nprof       !! profile length: sum_j (h_j + 1)
      real(dp), intent(out) :: mean_height    !! mean column height h_j = j - top_j
      integer, intent(out) :: max_height      !! largest column height (half-bandwidth)
      type(status_t), intent(inout) :: status !! STAT_SOLVER for an invalid graph
      integer, allocatable :: top(:)
      integer :: ierr, j
      character(len=:), allocatable :: msg

      nprof = 0
      mean_height = 0.0_dp
      max_height = 0
      allocate (top(max(neq, 0)))
      call column_tops(neq, xadj, adjncy, top, ierr, msg)
      if (ierr /= 0) then
         call status%set(STAT_SOLVER, msg)
         return
      end if
      do j = 1, neq
         nprof = nprof + int(j - top(j) + 1, i8)
         max_height = max(max_height, j - top(j))
      end do
      if (neq > 0) mean_height = real(nprof - neq, dp)/real(neq, dp)
   end subroutine graph_profile
end module graph
