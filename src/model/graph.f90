!> Node and equation adjacency graphs (CSR), built from the element
!! connectivity plus extra node-node links (contact pairs, ties, rigid-body
!! reference nodes).  The solvers take the equation graph to size their
!! storage once; the renumbering takes the node graph.
module graph
   use model, only: model_t
   use dof_map, only: dof_map_t
   use sorting, only: insertion_sort
   implicit none
   private
   public :: build_node_graph, build_equation_graph

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
end module graph
