!> Equation numbering for the driver: node order (reverse Cuthill-McKee or
!! the user's), DOF map, equation graph, and the profile before and after.
!!
!! The skyline solver's cost is set by its profile, so its equations follow
!! an RCM order of the node graph unless the deck says `RENUMBER NONE`.
!! UMFPACK orders the matrix itself (AMD), and the dense solver has no
!! profile, so by default they keep the user's order.  Whatever the order,
!! results are reported in the user's node numbers: only the equation
!! numbers change.
module equation_numbering
   use errors, only: status_t
   use run_plan, only: run_plan_t, ORDERING_RCM, ordering_name
   use model, only: model_t
   use records, only: numbering_report_t
   use dof_map, only: dof_map_t, build_dof_map
   use renumber, only: rcm_order
   use graph, only: build_node_graph, build_equation_graph, graph_profile
   implicit none
   private
   public :: numbering_report_t, number_equations

   ! numbering_report_t (what the numbering did) is a record (model layer): the listing
   ! prints it (listing's list_numbering)

contains

   !> Number the equations in the plan's order and build the equation graph.
   subroutine number_equations(m, plan, links, map, xadj, adjncy, rep, status, ties)
      type(model_t), intent(in) :: m
      type(run_plan_t), intent(in) :: plan          !! its ordering (RCM or the user's) and why
      integer, intent(in) :: links(:, :)            !! (2, nlink) extra node couplings
                                                    !! (contact pairs, ties)
      type(dof_map_t), intent(out) :: map
      integer, allocatable, intent(out) :: xadj(:), adjncy(:)   !! equation graph (CSR, 1-based)
      type(numbering_report_t), intent(out) :: rep
      type(status_t), intent(inout) :: status
      integer, intent(in), optional :: ties(:, :)   !! (3, ntie) master, slave, dof:
                                                    !! passed to build_dof_map
      integer, allocatable :: order(:), nxadj(:), nadj(:), x0(:), a0(:)
      type(dof_map_t) :: map0
      integer :: ip

      rep%method = ordering_name(plan%ordering)
      rep%reason = plan%ordering_reason

      call build_node_graph(m, links, nxadj, nadj)
      allocate (order(m%npoin))
      order = [(ip, ip=1, m%npoin)]
      if (present(ties)) then
         call build_dof_map(m, order, map0, ties)
      else
         call build_dof_map(m, order, map0)
      end if
      call build_equation_graph(map0, nxadj, nadj, x0, a0)
      call graph_profile(map0%neq, x0, a0, rep%profile_before, rep%mean_before, rep%max_before, &
                         status)
      if (.not. status%ok()) return
      if (plan%ordering /= ORDERING_RCM) then
         map = map0
         call move_alloc(x0, xadj)
         call move_alloc(a0, adjncy)
         rep%profile_after = rep%profile_before
         rep%mean_after = rep%mean_before
         rep%max_after = rep%max_before
         return
      end if
      deallocate (x0, a0)
      call rcm_order(m%npoin, nxadj, nadj, order)
      if (present(ties)) then
         call build_dof_map(m, order, map, ties)
      else
         call build_dof_map(m, order, map)
      end if
      call build_equation_graph(map, nxadj, nadj, xadj, adjncy)
      call graph_profile(map%neq, xadj, adjncy, rep%profile_after, rep%mean_after, rep%max_after, &
                         status)
   end subroutine number_equations
end module equation_numbering
