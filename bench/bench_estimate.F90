!> The cost of the error estimate against a linear solve of the same mesh, in
!! one run (tools/bench_estimate.py runs it per mesh):
!!
!!     bench_estimate NNODE NX [SOLVER [REPEAT]]
!!
!! A plane-strain block of NX x NX elements of NNODE nodes (4 or 8; 1 x 1,
!! graded 4:1 towards a corner so the patches are not all alike), clamped at
!! its base, a unit downward force at every top node (the model of
!! bench/bench_solvers.F90).  Timed: the solver's factorization and one solve
!! (SOLVER, default mumps; REPEAT times, the assembled matrix restored each
!! time), the stress recovery every run does
!! (body_fields::recover_stresses), the error estimate (error_estimate::
!! estimate_error) and the estimate as it was before its speed-up (the frozen
!! copy in bench/error_estimate_ref.f90), each REPEAT times (default 5; the
!! smallest time is taken: the machine is shared).
!! Output, one CSV line: nnode, nx, neq, solver, factorize_s, solve_s,
!! recover_s, estimate_s, estimate_ref_s, ratio (estimate_s / (factorize_s +
!! solve_s)), ratio_ref, max_diff (largest difference of the element
!! indicators, relative to the largest indicator), eta, eta_ref.
!! CPU times (cpu_time; OPENBLAS_NUM_THREADS=1 is the benchmark's setting).
program bench_estimate
   use kinds, only: dp
   use errors, only: status_t
   use model, only: model_t, material_t, restraint_t
   use mesh_generator, only: generate_block
   use dof_map, only: dof_map_t
   use equation_numbering, only: numbering_report_t, number_equations
   use run_plan, only: run_plan_t, ORDERING_USER
   use linear_solver, only: linear_solver_t
   use solver_factory, only: create_solver
   use assembly, only: coupling_t, assemble_bodies
   use records, only: body_fields_t, contact_fields_t
   use body_fields, only: recover_stresses, zero_fields
   use error_estimate, only: estimate_error
   use error_estimate_ref, only: estimate_error_ref
   implicit none

   type(model_t) :: m
   type(dof_map_t) :: map
   type(numbering_report_t) :: rep
   type(status_t) :: st
   type(coupling_t) :: coup
   type(body_fields_t) :: body, body_ref
   type(contact_fields_t) :: cf
   type(run_plan_t) :: plan
   class(linear_solver_t), allocatable :: s
   integer, allocatable :: xadj(:), adjncy(:), nolinks(:, :)
   real(dp), allocatable :: b(:), x(:)
   character(len=32) :: a_nnode, a_nx, a_solver, a_rep
   integer :: nnode, nx, ip, nrep, k, j
   real(dp) :: t0, t1, t_fa, t_so, t_rec, t_est, t_ref, diff

   call get_command_argument(1, a_nnode)
   call get_command_argument(2, a_nx)
   call get_command_argument(3, a_solver)
   call get_command_argument(4, a_rep)
   read (a_nnode, *) nnode
   read (a_nx, *) nx
   if (len_trim(a_solver) == 0) a_solver = 'mumps'
   nrep = 5
   if (len_trim(a_rep) > 0) read (a_rep, *) nrep

   m%title = 'bench'
   m%deck_file = 'bench.dat'
   m%ntype = 2
   m%solver_name = trim(a_solver)
   call generate_block(m, nnode, nx, nx, 0.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, 4.0_dp, 4.0_dp)
   m%nmats = 1
   allocate (m%mats(1))
   m%mats(1) = material_t(young=2.1e5_dp, poiss=0.3_dp, thick=1.0_dp)
   allocate (m%fixes(0), m%point_loads(0), m%edge_loads(0), m%body_loads(0))
   do ip = 1, m%npoin
      if (m%coord(2, ip) < 1.0e-12_dp) then
         m%fixes = [m%fixes, restraint_t(node=ip, fixed=[.true., .true.])]
      end if
   end do
   allocate (nolinks(2, 0))

   plan%ordering = ORDERING_USER       ! the mesh's order: the solvers order the equations
   plan%ordering_reason = 'the solver orders the equations'
   call number_equations(m, plan, nolinks, map, xadj, adjncy, rep, st)
   call create_solver(trim(a_solver), s, st)
   call check('create_solver')
   call s%analyse(map%neq, xadj, adjncy, st)
   call check('analyse')
   call assemble_bodies(m, map, s, coup, st)
   call check('assembly')
   call s%store_base()
   allocate (b(map%neq), x(map%neq))
   b = 0.0_dp
   do ip = 1, m%npoin
      if (m%coord(2, ip) > 1.0_dp - 1.0e-12_dp .and. map%id(2, ip) > 0) b(map%id(2, ip)) = -1.0_dp
   end do
   t_fa = huge(1.0_dp)
   t_so = huge(1.0_dp)
   do k = 1, nrep
      if (k > 1) call s%restore_base()
      call cpu_time(t0)
      call s%factorize(st)
      call check('factorize')
      call cpu_time(t1)
      t_fa = min(t_fa, t1 - t0)
      x = b
      call cpu_time(t0)
      call s%solve(x, st)
      call check('solve')
      call cpu_time(t1)
      t_so = min(t_so, t1 - t0)
   end do
   b = x

   call zero_fields(m, body)
   do ip = 1, m%npoin
      do j = 1, 2
         if (map%id(j, ip) > 0) body%disp(j, ip) = b(map%id(j, ip))
      end do
   end do
   t_rec = huge(1.0_dp)
   t_est = huge(1.0_dp)
   t_ref = huge(1.0_dp)
   do k = 1, nrep
      call cpu_time(t0)
      call recover_stresses(m, body, st)
      call check('recover_stresses')
      call cpu_time(t1)
      t_rec = min(t_rec, t1 - t0)
      body_ref = body
      call cpu_time(t0)
      call estimate_error_ref(m, body_ref, cf, st)
      call check('estimate_error_ref')
      call cpu_time(t1)
      t_ref = min(t_ref, t1 - t0)
      call cpu_time(t0)
      call estimate_error(m, body, cf, st)
      call check('estimate_error')
      call cpu_time(t1)
      t_est = min(t_est, t1 - t0)
   end do
   diff = maxval(abs(body%error_indicator - body_ref%error_indicator)) &
          /maxval(body_ref%error_indicator)

   write (*, '(i0,",",i0,",",i0,",",a,7(",",es10.3),",",es9.2,2(",",es16.9))') nnode, nx, map%neq, &
      trim(a_solver), t_fa, t_so, t_rec, t_est, t_ref, t_est/(t_fa + t_so), t_ref/(t_fa + t_so), &
      diff, &
      body%estimated_error, body_ref%estimated_error
contains
   subroutine check(what)
      character(len=*), intent(in) :: what
      if (.not. st%ok()) then
         write (*, '(a)') 'bench_estimate: '//what//' failed: '//st%message
         error stop 1
      end if
   end subroutine check
end program bench_estimate
