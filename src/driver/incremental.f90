!> The incremental driver: owns the loop over load increments.
!!
!! Set-up: equation numbering (with ties), the equation graph including every
!! contact pair, symbolic analysis, K_AB assembled once (bodies are linear
!! elastic, small strain: eq. 4.12) and kept in the solver as its base matrix,
!! load vectors of every load case.
!!
!! Increment i (eqs. 3.15, 3.37, 3.38): the factors of the load cases scale the
!! external forces and the prescribed displacements; the contact springs get
!! their modes and stiffnesses from the previous increment; then
!!
!!     repeat:  [K_AB + K_c] dv = b        (b = load increment + carried
!!                                          out-of-balance, then the residual)
!!              evaluate the springs for the increment so far
!!              residual = predicted - actual spring forces
!!     until no spring changes its mode and the residual vanishes
!!
!! (for the paper's explicit update a repeat is the paper's repetition of the
!! increment with new stiffnesses, solved for the correction).  Ideal contact
!! (augmented Lagrangian, contact_algorithm) adds an outer step to the same
!! loop: once the modes settle and the residual vanishes, the multipliers are
!! updated (Uzawa) and the loop goes on until the penetration is below its
!! tolerance; every pass is one solution, all count against CONTACT REPEATS.
!! Totals are sums of increments (eqs. 3.34-3.36).  Stresses, reactions and the contact
!! quantities are written to the HDF5 file, which is flushed.
!!
!! A numerical failure stops the loop cleanly: every finished increment stays
!! in the result file, whose status attribute says what happened.
module incremental
   use kinds, only: dp, stdout, stderr
   use errors, only: status_t, STAT_SINGULAR, STAT_INPUT, STAT_IO, STAT_JACOBIAN, STAT_NO_CONVERGENCE
   use strings, only: itoa, rtoa, strip_extension, basename
   use model, only: model_t, MAX_NODE
   use dof_map, only: dof_map_t, build_dof_map
   use graph, only: build_node_graph, build_equation_graph
   use linear_solver, only: linear_solver_t
   use solver_factory, only: create_solver
   use assembly, only: coupling_t, assemble_bodies, assemble_load_cases, &
                       subtract_prescribed, restrained_forces, element_error
   use solid2d, only: element_stresses
   use quadrature, only: max_gp
   use contact_types, only: UPDATE_RETURN, contact_pair_t, MAX_PAIR_NODES, LAW_ROUGH, PAIR_RIGID
   use contact_algorithm, only: contact_state_t, contact_init, begin_increment, pair_matrix, &
                                evaluate_pairs, commit_increment, pair_force_vector, law_drift, check_invariants, &
                                augment_multipliers, pair_dofs, NS_OPEN, NS_LOADING, NS_UNLOADING, TS_SLIP
   use restraint_check, only: find_bodies
   use results_hdf5, only: results_file_t, K2D_VERSION
   use listing, only: list_header, list_input, list_displacements, list_stresses, list_contact
   use hdf5, only: hid_t
   implicit none
   private
   public :: run_options_t, run_result_t, run_analysis, recover_stresses

   !> Choices of the command line that override or complement the deck.
   type :: run_options_t
      character(len=:), allocatable :: results_path   !! HDF5 file ('' = <deck>.h5 in the working directory)
      character(len=:), allocatable :: listing_path   !! listing file ('' = <results>.lis)
      character(len=:), allocatable :: solver_name    !! '' = the deck's choice
      logical :: quiet = .false.                      !! no terminal output except errors
   end type run_options_t

   !> What a run leaves in memory (used by the tests and the caller).
   type :: run_result_t
      integer :: completed = 0                   !! increments finished
      real(dp), allocatable :: disp(:, :)        !! (2, npoin) total displacements
      real(dp), allocatable :: react(:, :)       !! (2, npoin) reactions
      real(dp), allocatable :: sig_nd(:, :)      !! (4, npoin) averaged nodal stresses
      real(dp), allocatable :: sig_gp(:, :)      !! (4, ngp) Gauss-point stresses
      real(dp), allocatable :: xygp(:, :)        !! (2, ngp)
      integer, allocatable :: gp_start(:)        !! (nelem+1)
      type(contact_state_t) :: contact           !! committed contact states
      integer, allocatable :: iterations(:)      !! solves per increment
      integer, allocatable :: repeats(:)         !! repeats (mode changes) per increment
      real(dp), allocatable :: residual(:)       !! relative out-of-balance force after each increment
      real(dp), allocatable :: drift(:)          !! largest departure of F_n from its curve, relative
      real(dp), allocatable :: imbalance(:)      !! largest force imbalance of a body, relative
      integer, allocatable :: violations(:)      !! invariant violations per increment (SPEC §7)
      real(dp), allocatable :: penetration(:)    !! ideal contact: largest |u_n| (closed) or stick slip at the end
      integer, allocatable :: augmentations(:)   !! ideal contact: multiplier updates per increment
      character(len=:), allocatable :: results_path
   end type run_result_t

contains

   !> Solve the model through its load history.
   subroutine run_analysis(m, opts, res, status)
      type(model_t), intent(inout) :: m
      type(run_options_t), intent(in) :: opts
      type(run_result_t), intent(out) :: res
      type(status_t), intent(inout) :: status
      type(dof_map_t) :: map
      class(linear_solver_t), allocatable :: solver
      type(coupling_t) :: coup
      type(results_file_t) :: rf
      integer, allocatable :: order(:), nxadj(:), nadj(:), xadj(:), adjncy(:), links(:, :), peq(:, :)
      real(dp), allocatable :: fcase(:, :, :), ucase(:, :, :), fext(:, :), du(:, :), ddu(:, :), rhs(:), fr(:, :)
      real(dp), allocatable :: dlam(:), carry(:), rvec(:, :), rpred(:, :), kstore(:, :, :), fsp(:, :)
      logical, allocatable :: restrained(:, :), changed(:)
      integer :: ip, inc, idof, lu, ic, j, iter, nrep, npair, nd, k, nlink, maxrep
      logical :: have_lis, augmented
      integer(hid_t) :: gid
      integer(kind=8) :: t0, t1, rate
      character(len=:), allocatable :: solver_name, lis_path, lis_level
      logical :: has_contact, need_factor, converged, returning
      real(dp) :: fscale, rnorm, gap_tol, force_scale
      real(dp), allocatable :: ve_old(:)
      integer, allocatable :: body(:)
      integer :: nbody, nbad
      character(len=:), allocatable :: imsg

      call system_clock(t0, rate)
      call complete_model(m)
      has_contact = m%contact%active
      npair = size(m%contact%pairs)
      returning = m%contact%opts%update == UPDATE_RETURN
      solver_name = m%solver_name
      if (allocated(opts%solver_name)) then
         if (len(opts%solver_name) > 0) solver_name = opts%solver_name
      end if
      res%results_path = strip_extension(basename(m%deck_file))//'.h5'
      if (allocated(opts%results_path)) then
         if (len(opts%results_path) > 0) res%results_path = opts%results_path
      end if
      lis_path = strip_extension(res%results_path)//'.lis'
      if (allocated(opts%listing_path)) then
         if (len(opts%listing_path) > 0) lis_path = opts%listing_path
      end if
      lis_level = m%listing_level

      ! ---- equations (ties share equations), pattern with every pair, K_AB
      nlink = 0
      do j = 1, npair
         nlink = nlink + (m%contact%pairs(j)%nn*(m%contact%pairs(j)%nn - 1))/2
      end do
      allocate (order(m%npoin), links(2, nlink))
      order = [(ip, ip=1, m%npoin)]
      nlink = 0
      do j = 1, npair
         ! all nodes of a pair couple: node a with its master side (node b, the
         ! nodes of B under its tributary zone, or a rigid body's reference
         ! node), and those master nodes with each other
         do k = 2, m%contact%pairs(j)%nn
            do ip = 1, k - 1
               nlink = nlink + 1
               links(:, nlink) = [m%contact%pairs(j)%nodes(ip), m%contact%pairs(j)%nodes(k)]
            end do
         end do
      end do
      call build_dof_map(m, order, map, m%ties)
      call build_node_graph(m, links, nxadj, nadj)
      call build_equation_graph(map, nxadj, nadj, xadj, adjncy)
      call create_solver(solver_name, solver, status)
      if (.not. status%ok()) then
         status%code = STAT_INPUT
         return
      end if
      call solver%analyse(map%neq, xadj, adjncy, status)
      if (.not. status%ok()) return
      call solver%zero()
      call assemble_bodies(m, map, solver, coup, status)
      if (.not. status%ok()) return
      call solver%store_base()
      call assemble_load_cases(m, fcase, ucase, status)
      if (.not. status%ok()) return

      allocate (restrained(2, m%npoin))
      restrained = map%id < 0
      allocate (res%disp(2, m%npoin), res%react(2, m%npoin), fext(2, m%npoin), du(2, m%npoin), &
                ddu(2, m%npoin), rhs(map%neq), fr(2, m%npoin), dlam(m%ncase), carry(map%neq), fsp(2, m%npoin))
      allocate (res%iterations(m%nincs), res%repeats(m%nincs), res%residual(m%nincs), res%drift(m%nincs))
      allocate (res%imbalance(m%nincs), res%violations(m%nincs), ve_old(npair))
      allocate (res%penetration(m%nincs), res%augmentations(m%nincs))
      res%penetration = 0.0_dp
      res%augmentations = 0
      res%imbalance = 0.0_dp
      res%violations = 0
      force_scale = tiny(1.0_dp)
      res%iterations = 0
      res%repeats = 0
      res%residual = 0.0_dp
      res%drift = 0.0_dp
      res%disp = 0.0_dp
      res%react = 0.0_dp
      fext = 0.0_dp
      carry = 0.0_dp

      ! ---- contact: initial states, start pressure of eq. (4.1)
      nd = 2*MAX_PAIR_NODES
      allocate (rvec(nd, npair), rpred(nd, npair), kstore(nd, nd, npair), changed(npair), peq(nd, npair))
      peq = 0
      rvec = 0.0_dp
      rpred = 0.0_dp
      kstore = 0.0_dp
      do j = 1, npair
         do k = 1, m%contact%pairs(j)%nn
            peq(2*k - 1:2*k, j) = map%id(:, m%contact%pairs(j)%nodes(k))
         end do
      end do
      gap_tol = m%contact%opts%gap_tol
      if (gap_tol < 0.0_dp) gap_tol = 1.0e-9_dp*model_size(m)
      call contact_init(m%contact, gap_tol, res%contact)
      ! the cap on solutions per increment: CONTACT REPEATS, or 30 for the
      ! rough springs and 100 when the augmented Lagrangian of an ideal
      ! interface has to converge too
      maxrep = max(1, m%contact%opts%max_repeats)
      if (res%contact%has_ideal .and. .not. m%contact%opts%repeats_given) maxrep = 100
      m%contact%opts%max_repeats = maxrep          ! as used (result file, listing)
      allocate (body(m%npoin))
      call find_bodies(m, reshape([integer ::], [2, 0]), body, nbody)
      ! a rigid body's reference node belongs to no element: a body of its own
      do j = 1, npair
         if (m%contact%pairs(j)%kind /= PAIR_RIGID) cycle
         if (body(m%contact%pairs(j)%node_b) > 0) cycle
         nbody = nbody + 1
         body(m%contact%pairs(j)%node_b) = nbody
      end do
      if (has_contact .and. res%contact%has_rough) then
         call start_pressure(m, fcase, m%lambda(:, 1) - m%lambda(:, 0), res%contact, status)
         if (.not. status%ok()) return
      end if

      ! ---- stress recovery layout (Gauss points are fixed)
      call recover_stresses(m, res%disp, res%gp_start, res%xygp, res%sig_gp, res%sig_nd, status)
      if (.not. status%ok()) return

      ! ---- result file and listing
      call rf%create(res%results_path, m, res%gp_start(2:) - res%gp_start(:m%nelem), res%xygp, status)
      if (.not. status%ok()) return
      if (has_contact) then
         call rf%write_contact_definition(m%contact, status)
         if (.not. status%ok()) return
      end if
      have_lis = lis_level /= 'NONE'
      lu = 0
      if (have_lis) then
         open (newunit=lu, file=lis_path, status='replace', action='write')
         call list_header(lu, m, K2D_VERSION, solver%name(), map%neq, map%nres)
         if (lis_level == 'FULL') call list_input(lu, m)
      end if
      if (.not. opts%quiet) then
         call list_header(stdout, m, K2D_VERSION, solver%name(), map%neq, map%nres)
         write (stdout, '(a)') ' Results      : '//res%results_path
         if (have_lis) write (stdout, '(a)') ' Listing      : '//lis_path
         write (stdout, '(a)') repeat('-', 78)
         if (has_contact) then
            write (stdout, '(a)') '   inc  load factor     max |u|  closed  slip  solves rep   residual    time [s]'
         else
            write (stdout, '(a)') '   inc  load factor     max |u|        sum Rx        sum Ry    time [s]'
         end if
      end if

      ! ---- the loop over increments
      need_factor = .true.
      do inc = 1, m%nincs
         dlam = m%lambda(:, inc) - m%lambda(:, inc - 1)
         du = 0.0_dp
         rhs = carry
         do ic = 1, m%ncase
            fext = fext + dlam(ic)*fcase(:, :, ic)
            where (restrained) du = du + dlam(ic)*ucase(:, :, ic)
         end do
         do ip = 1, m%npoin
            do idof = 1, 2
               if (map%id(idof, ip) > 0) rhs(map%id(idof, ip)) = rhs(map%id(idof, ip)) + sum(dlam*fcase(idof, ip, :))
            end do
         end do
         call subtract_prescribed(coup, map, du, rhs)
         fscale = max(maxval(abs(rhs)), maxval(abs(fext)), 1.0e-300_dp)

         ! spring forces at the start of the increment
         if (has_contact) then
            call begin_increment(m%contact, res%contact, inc == 1)
            do j = 1, npair
               call pair_force_vector(m%contact, j, res%contact%s(j)%fn, res%contact%s(j)%ft, rvec(:, j))
            end do
            need_factor = .true.
         end if

         ! repeat the increment until the springs keep their modes and balance
         ddu = du           ! first solve: prescribed increments at the restrained dofs
         nrep = 0
         converged = .false.
         augmented = .false.
         do iter = 1, maxrep
            if (need_factor) then
               call solver%restore_base()
               do j = 1, npair
                  call pair_matrix(m%contact, res%contact, j, kstore(:, :, j))
                  call solver%add_element(peq(:, j), kstore(:, :, j))
               end do
               call solver%factorize(status)
               if (.not. status%ok()) then
                  if (status%code == STAT_SINGULAR .and. solver%failed_equation() > 0) then
                     status%message = 'singular or unrestrained model at '// &
                                      map%describe(solver%failed_equation())//': '//status%message
                  end if
                  exit
               end if
               need_factor = has_contact .and. returning
            end if
            if (iter == 1) then
               call subtract_contact_prescribed(peq, kstore, m%contact%pairs, ddu, rhs)
               ! an increment driven only through springs of prescribed nodes (a
               ! rigid body's reference node belongs to no element) has no other
               ! force to measure its out-of-balance force against
               if (fscale <= 1.0e-300_dp .and. map%neq > 0) fscale = max(maxval(abs(rhs)), 1.0e-300_dp)
            end if
            call solver%solve(rhs, status)
            if (.not. status%ok()) exit
            do ip = 1, m%npoin
               do idof = 1, 2
                  if (map%id(idof, ip) > 0) ddu(idof, ip) = rhs(map%id(idof, ip))
               end do
            end do
            du = du + merge(0.0_dp, ddu, restrained)
            if (.not. has_contact) then
               converged = .true.
               exit
            end if
            ! predicted spring forces (the linearisation the solve used) ...
            do j = 1, npair
               k = 2*m%contact%pairs(j)%nn
               rpred(1:k, j) = rvec(1:k, j) + matmul(kstore(1:k, 1:k, j), pair_values(ddu, m%contact%pairs(j), k))
            end do
            ! ... against the actual ones, after the mode checks
            call evaluate_pairs(m%contact, res%contact, du, changed, inc == 1)
            call residual_forces()
            ddu = 0.0_dp
            if (any(changed)) then
               nrep = nrep + 1
               need_factor = .true.
               cycle
            end if
            if (rnorm <= m%contact%opts%tol_residual) then
               if (.not. res%contact%has_ideal) then
                  converged = .true.
                  exit
               end if
               ! ideal contact: the modes hold and the bodies balance the
               ! forces of the current multipliers; converged when the
               ! penetrations are within tolerance, else an Uzawa update and
               ! the forces of the new multipliers drive the next solution
               call augment_multipliers(m%contact, res%contact, augmented)
               if (augmented) then
                  converged = .true.
                  exit
               end if
               call evaluate_pairs(m%contact, res%contact, du, changed, inc == 1)
               call residual_forces()
               if (any(changed)) then
                  nrep = nrep + 1
                  need_factor = .true.
               end if
            end if
         end do
         if (.not. status%ok()) exit
         res%iterations(inc) = iter
         if (iter > maxrep) res%iterations(inc) = iter - 1
         res%repeats(inc) = nrep
         res%augmentations(inc) = res%contact%augmentations
         res%penetration(inc) = res%contact%violation
         if (has_contact) then
            res%residual(inc) = rnorm
            carry = rhs
            if (.not. converged .and. (returning .or. any(changed) .or. res%contact%has_ideal)) then
               if (any(changed)) then
                  call status%set(STAT_NO_CONVERGENCE, 'no convergence in increment '//itoa(inc)//' after '// &
                                  itoa(res%iterations(inc))//' solutions (contact states keep changing); '// &
                                  'reduce the increment size or raise CONTACT REPEATS')
               else if (res%contact%has_ideal .and. rnorm <= m%contact%opts%tol_residual) then
                  call status%set(STAT_NO_CONVERGENCE, 'no convergence in increment '//itoa(inc)//' after '// &
                                  itoa(res%iterations(inc))//' solutions: ideal contact still penetrates or '// &
                                  'slips by '//rtoa(res%contact%violation)//' > the tolerance '// &
                                  rtoa(res%contact%tol_pen)//' after '//itoa(res%contact%augmentations)// &
                                  ' multiplier updates; raise CONTACT REPEATS or the AUGMENTED factor')
               else
                  call status%set(STAT_NO_CONVERGENCE, 'no convergence in increment '//itoa(inc)//' after '// &
                                  itoa(res%iterations(inc))//' solutions (relative out-of-balance force '// &
                                  rtoa(rnorm)//'); reduce the increment size or raise CONTACT REPEATS')
               end if
               exit
            end if
            ve_old = res%contact%s%ve
            call commit_increment(m%contact, res%contact)
            res%drift(inc) = law_drift(m%contact, res%contact)
         end if
         res%disp = res%disp + du

         ! ---- post-processing
         call recover_stresses(m, res%disp, res%gp_start, res%xygp, res%sig_gp, res%sig_nd, status)
         if (.not. status%ok()) exit
         call restrained_forces(coup, map, res%disp, fr)
         fsp = 0.0_dp
         do j = 1, npair
            call pair_force_vector(m%contact, j, res%contact%s(j)%fn, res%contact%s(j)%ft, rvec(:, j))
            do k = 1, m%contact%pairs(j)%nn
               fsp(:, m%contact%pairs(j)%nodes(k)) = fsp(:, m%contact%pairs(j)%nodes(k)) + rvec(2*k - 1:2*k, j)
            end do
         end do
         res%react = 0.0_dp
         where (restrained) res%react = fr + fsp - fext

         ! invariants (SPEC §7): every body in equilibrium under loads, reactions
         ! and spring forces; no tension; |F_T| <= mu F_n; v_e non-decreasing
         force_scale = max(force_scale, maxval(abs(fext)), maxval(abs(res%react)), maxval(abs(fsp)))
         res%imbalance(inc) = body_imbalance(body, nbody, fext + res%react - fsp, force_scale, m%ntype == 3)
         nbad = 0
         imsg = ''
         if (has_contact) call check_invariants(res%contact, ve_old, nbad, imsg)
         if (res%imbalance(inc) > 1.0e-8_dp) then
            nbad = nbad + 1
            imsg = 'a body is out of equilibrium by '//rtoa(res%imbalance(inc))//' of the load'
         end if
         res%violations(inc) = nbad
         if (nbad > 0) write (stderr, '(a)') 'kontakt2d: warning: increment '//itoa(inc)//': '//itoa(nbad)// &
            ' invariant violation(s): '//imsg

         call rf%open_increment(inc, m%lambda(:, inc), res%iterations(inc), nrep, converged, gid, status)
         if (.not. status%ok()) exit
         block
            integer :: err
            err = 0
            call rf%write_real2(gid, 'displacement', res%disp, err)
            call rf%write_real2(gid, 'stress_nodal', res%sig_nd, err)
            call rf%write_real2(gid, 'stress_gauss', res%sig_gp, err)
            call rf%write_real2(gid, 'reaction', res%react, err)
            if (has_contact) call rf%attr_real0(gid, 'residual', res%residual(inc), err)
            if (has_contact) call rf%attr_real0(gid, 'law_drift', res%drift(inc), err)
            if (res%contact%has_ideal) call rf%attr_real0(gid, 'penetration', res%penetration(inc), err)
            if (res%contact%has_ideal) call rf%attr_int(gid, 'augmentations', res%augmentations(inc), err)
            call rf%attr_real0(gid, 'imbalance', res%imbalance(inc), err)
            call rf%attr_int(gid, 'invariant_violations', res%violations(inc), err)
            if (err < 0) call status%set(STAT_IO, 'HDF5: cannot write the results of increment '//itoa(inc))
         end block
         if (has_contact .and. status%ok()) call write_contact_results(rf, gid, m, res%contact, status)
         if (.not. status%ok()) exit
         call rf%close_increment(gid, status)
         if (.not. status%ok()) exit
         res%completed = inc

         if (have_lis .and. (lis_level == 'FULL' .or. inc == m%nincs)) then
            call list_displacements(lu, m, inc, m%lambda(:, inc), res%disp, res%react, restrained)
            if (has_contact) call list_contact(lu, m%contact, res%contact, res%iterations(inc), nrep, &
                                               res%residual(inc), res%drift(inc))
            call list_stresses(lu, m, res%gp_start, res%xygp, res%sig_gp)
         end if
         call system_clock(t1)
         if (.not. opts%quiet) then
            if (has_contact) then
               write (stdout, '(i6, f13.5, es12.4, i8, i6, i8, i4, es11.3, f12.3)') inc, maxval(abs(m%lambda(:, inc))), &
                  maxval(sqrt(res%disp(1, :)**2 + res%disp(2, :)**2)), count(res%contact%s%closed), &
                  count(res%contact%s%closed .and. res%contact%s%tstate == TS_SLIP), res%iterations(inc), nrep, &
                  res%residual(inc), real(t1 - t0, dp)/real(rate, dp)
            else
               write (stdout, '(i6, f13.5, 3es14.5, f12.3)') inc, maxval(abs(m%lambda(:, inc))), &
                  maxval(sqrt(res%disp(1, :)**2 + res%disp(2, :)**2)), sum(res%react(1, :)), &
                  sum(res%react(2, :)), real(t1 - t0, dp)/real(rate, dp)
            end if
            flush (stdout)
         end if
      end do

      if (status%ok()) then
         call rf%set_status('completed')
         if (.not. opts%quiet) then
            write (stdout, '(a)') repeat('-', 78)
            write (stdout, '(a)') ' Completed '//itoa(res%completed)//' increment(s); results in '//res%results_path
         end if
      else
         call rf%set_status('failed at increment '//itoa(res%completed + 1)//': '//status%message)
         write (stderr, '(a)') 'kontakt2d: increment '//itoa(res%completed + 1)//' failed: '//status%message
         write (stderr, '(a)') 'kontakt2d: '//itoa(res%completed)//' completed increment(s) are kept in '// &
            res%results_path
      end if
      call rf%close()
      if (have_lis) close (lu)
      call solver%free()
   contains
      !> Internal-force vectors of the pairs for their current forces, and the
      !! out-of-balance force: the forces the solve predicted minus these.
      subroutine residual_forces()
         integer :: jp, nv
         do jp = 1, npair
            call pair_force_vector(m%contact, jp, res%contact%fn(jp), res%contact%ft(jp), rvec(:, jp))
         end do
         rhs = 0.0_dp
         do jp = 1, npair
            nv = 2*m%contact%pairs(jp)%nn
            call scatter_free(peq(1:nv, jp), rpred(1:nv, jp) - rvec(1:nv, jp), rhs)
         end do
         rnorm = 0.0_dp
         if (map%neq > 0) rnorm = maxval(abs(rhs))/fscale
      end subroutine residual_forces
   end subroutine run_analysis

   !> Largest |sum of the forces on a body| relative to the force scale of the run.
   !! In axisymmetry only the axial sum: radial ring forces are balanced by the
   !! hoop stresses, not by each other.
   pure real(dp) function body_imbalance(body, nbody, f, scale, axisymmetric) result(worst)
      integer, intent(in) :: body(:), nbody
      real(dp), intent(in) :: f(:, :)        !! (2, npoin) external + reactions - spring internal forces
      real(dp), intent(in) :: scale          !! largest nodal force seen so far
      logical, intent(in) :: axisymmetric
      real(dp) :: total(2, max(nbody, 1))
      integer :: ip
      total = 0.0_dp
      do ip = 1, size(body)
         if (body(ip) > 0) total(:, body(ip)) = total(:, body(ip)) + f(:, ip)
      end do
      if (axisymmetric) total(1, :) = 0.0_dp
      worst = maxval(abs(total))/scale
   end function body_imbalance

   !> Give a model built in code the empty parts a deck would have.
   subroutine complete_model(m)
      type(model_t), intent(inout) :: m
      if (.not. allocated(m%ties)) allocate (m%ties(3, 0))
      if (.not. allocated(m%contact%pairs)) allocate (m%contact%pairs(0))
      if (.not. allocated(m%contact%ifaces)) allocate (m%contact%ifaces(0))
      if (.not. allocated(m%contact%rigids)) allocate (m%contact%rigids(0))
      m%contact%active = size(m%contact%pairs) > 0
   end subroutine complete_model

   pure real(dp) function model_size(m)
      type(model_t), intent(in) :: m
      model_size = max(maxval(m%coord(1, :)) - minval(m%coord(1, :)), maxval(m%coord(2, :)) - minval(m%coord(2, :)))
   end function model_size

   !> The nd = 2 nn dof values (a_x, a_y, b_x, b_y, ...) of a pair from a nodal field.
   pure function pair_values(v, pr, nd) result(x)
      real(dp), intent(in) :: v(:, :)
      type(contact_pair_t), intent(in) :: pr
      integer, intent(in) :: nd
      real(dp) :: x(nd), y(2*MAX_PAIR_NODES)
      y = pair_dofs(v, pr)
      x = y(1:nd)
   end function pair_values

   !> Add a pair's vector to the free equations (entries with ieq <= 0 are skipped).
   pure subroutine scatter_free(ieq, v, b)
      integer, intent(in) :: ieq(:)
      real(dp), intent(in) :: v(:)
      real(dp), intent(inout) :: b(:)
      integer :: k
      do k = 1, size(ieq)
         if (ieq(k) > 0) b(ieq(k)) = b(ieq(k)) + v(k)
      end do
   end subroutine scatter_free

   !> b(free) -= K_c u_r: springs attached to prescribed displacements.
   pure subroutine subtract_contact_prescribed(peq, kstore, pairs, u, b)
      integer, intent(in) :: peq(:, :)
      real(dp), intent(in) :: kstore(:, :, :)
      type(contact_pair_t), intent(in) :: pairs(:)
      real(dp), intent(in) :: u(:, :)
      real(dp), intent(inout) :: b(:)
      real(dp), allocatable :: x(:)
      integer :: j, nd
      do j = 1, size(pairs)
         nd = 2*pairs(j)%nn
         if (all(peq(1:nd, j) > 0)) cycle
         x = pair_values(u, pairs(j), nd)
         where (peq(1:nd, j) > 0) x = 0.0_dp
         call scatter_free(peq(1:nd, j), -matmul(kstore(1:nd, 1:nd, j), x), b)
      end do
   end subroutine subtract_contact_prescribed

   !> Start pressure p_m of eq. (4.1) for the rough interfaces: the resultant
   !! of the first load increment on body A, projected on the mean contact
   !! normal, over the nominal area of the initially closed pairs; or START PM.
   !! When body A carries no load (e.g. a foundation under a loaded punch, or a
   !! half-space under a rigid body driven through its reference node) the
   !! resultant on the bodies of side B is taken instead: both balance the
   !! same contact force.
   subroutine start_pressure(m, fcase, dlam1, st, status)
      type(model_t), intent(in) :: m
      real(dp), intent(in) :: fcase(:, :, :), dlam1(:)
      type(contact_state_t), intent(inout) :: st
      type(status_t), intent(inout) :: status
      integer, allocatable :: body(:), nolinks(:, :)
      logical, allocatable :: in_a(:), in_b(:)
      real(dp) :: nbar(2), aa, fn
      integer :: nbody, j, k
      logical :: any_closed

      st%p_start = m%contact%opts%p_start
      if (st%p_start > 0.0_dp) return
      allocate (body(m%npoin), nolinks(2, 0), in_a(m%npoin), in_b(m%npoin))
      call find_bodies(m, nolinks, body, nbody)
      in_a = .false.
      in_b = .false.
      nbar = 0.0_dp
      aa = 0.0_dp
      any_closed = .false.
      do j = 1, size(m%contact%pairs)
         associate (pr => m%contact%pairs(j))
            if (m%contact%ifaces(pr%iface)%law /= LAW_ROUGH) cycle
            if (body(pr%node_a) > 0) in_a = in_a .or. body == body(pr%node_a)
            do k = 2, pr%nn
               if (body(pr%nodes(k)) > 0) then
                  in_b = in_b .or. body == body(pr%nodes(k))
               else
                  in_b(pr%nodes(k)) = .true.      ! a rigid body's reference node
               end if
            end do
            if (.not. st%s(j)%closed) cycle
            any_closed = .true.
            aa = aa + pr%area
            nbar = nbar + pr%area*pr%n
         end associate
      end do
      if (.not. any_closed) then
         st%p_start = 0.0_dp
         return
      end if
      nbar = nbar/max(norm2(nbar), tiny(1.0_dp))
      fn = abs(dot_product(resultant(in_a), nbar))
      if (.not. (fn > 0.0_dp)) fn = abs(dot_product(resultant(in_b .and. .not. in_a), nbar))
      if (.not. (fn > 0.0_dp) .or. .not. (aa > 0.0_dp)) then
         call status%set(STAT_INPUT, 'contact: the first increment applies no force normal to the contact '// &
                         'surface on either body (it is displacement-driven), so the start pressure p_m of eq. (4.1) '// &
                         'cannot be computed; give it on a CONTACT START card (PM)')
         return
      end if
      st%p_start = fn/aa
   contains
      !> Resultant of the first load increment on the flagged nodes.
      function resultant(flag) result(f)
         logical, intent(in) :: flag(:)
         real(dp) :: f(2), df(2)
         integer :: ip, ic
         f = 0.0_dp
         do ip = 1, m%npoin
            if (.not. flag(ip)) cycle
            do ic = 1, size(dlam1)
               df = dlam1(ic)*fcase(:, ip, ic)
               f = f + df
            end do
         end do
      end function resultant
   end subroutine start_pressure

   !> Contact quantities of one increment into its group `contact`.
   subroutine write_contact_results(rf, gid, m, st, status)
      type(results_file_t), intent(inout) :: rf
      integer(hid_t), intent(in) :: gid
      type(model_t), intent(in) :: m
      type(contact_state_t), intent(in) :: st
      type(status_t), intent(inout) :: status
      real(dp), allocatable :: area(:), pn(:), pt(:)
      integer, allocatable :: nstate(:), tstate(:)
      integer :: j, np
      np = size(m%contact%pairs)
      allocate (area(np), pn(np), pt(np), nstate(np), tstate(np))
      area = m%contact%pairs%area
      where (area > 0.0_dp)
         pn = st%s%fn/area
         pt = st%s%ft/area
      elsewhere
         pn = 0.0_dp
         pt = 0.0_dp
      end where
      call extrapolate_zero_area(m, pn)
      call extrapolate_zero_area(m, pt)
      do j = 1, np
         if (.not. st%s(j)%closed) then
            nstate(j) = NS_OPEN
         else if (st%s(j)%on_unloading) then
            nstate(j) = NS_UNLOADING
         else
            nstate(j) = NS_LOADING
         end if
         tstate(j) = st%s(j)%tstate
      end do
      call rf%write_contact_increment(gid, pn, pt, st%s%fn, st%s%ft, st%s%un, st%s%ut, st%s%utp, &
                                      st%s%utp_gross, st%s%ve, st%s%mu, nstate, tstate, st%s%kn, st%s%kt, status)
   end subroutine write_contact_results

   !> Pairs of zero area (a quadratic axisymmetric edge on the axis) carry no
   !! spring; report their stress by linear extrapolation from the two
   !! nearest pairs of the same interface (SPEC §3.2 caveat).
   subroutine extrapolate_zero_area(m, v)
      type(model_t), intent(in) :: m
      real(dp), intent(inout) :: v(:)
      integer :: j, k, k1, k2
      real(dp) :: d, d1, d2
      do j = 1, size(v)
         if (m%contact%pairs(j)%area > 0.0_dp) cycle
         k1 = 0
         k2 = 0
         d1 = huge(1.0_dp)
         d2 = huge(1.0_dp)
         do k = 1, size(v)
            if (k == j .or. m%contact%pairs(k)%area <= 0.0_dp) cycle
            if (m%contact%pairs(k)%iface /= m%contact%pairs(j)%iface) cycle
            d = norm2(m%contact%pairs(k)%position - m%contact%pairs(j)%position)
            if (d < d1) then
               k2 = k1
               d2 = d1
               k1 = k
               d1 = d
            else if (d < d2) then
               k2 = k
               d2 = d
            end if
         end do
         if (k1 > 0 .and. k2 > 0 .and. d2 > d1) then
            v(j) = v(k1) + (v(k1) - v(k2))*d1/(d2 - d1)
         else if (k1 > 0) then
            v(j) = v(k1)
         end if
      end do
   end subroutine extrapolate_zero_area

   !> Stresses at every Gauss point and averaged at the nodes.
   subroutine recover_stresses(m, disp, gp_start, xygp, sig_gp, sig_nd, status)
      type(model_t), intent(in) :: m
      real(dp), intent(in) :: disp(:, :)
      integer, allocatable, intent(inout) :: gp_start(:)
      real(dp), allocatable, intent(inout) :: xygp(:, :), sig_gp(:, :), sig_nd(:, :)
      type(status_t), intent(inout) :: status
      real(dp) :: elcod(2, MAX_NODE), eldis(2*MAX_NODE), xyg(2, max_gp), sg(4, max_gp), sn(4, MAX_NODE)
      real(dp), allocatable :: cnt(:)
      integer :: ie, nn, ngp, ierr, k, imat

      if (.not. allocated(gp_start)) then
         ! first call: count the Gauss points
         allocate (gp_start(m%nelem + 1))
         gp_start(1) = 1
         do ie = 1, m%nelem
            nn = m%nnode_e(ie)
            elcod(:, 1:nn) = m%coord(:, m%lnods(1:nn, ie))
            imat = m%matno(ie)
            call element_stresses(m%ntype, nn, elcod(:, 1:nn), m%mats(imat)%young, m%mats(imat)%poiss, &
                                  m%ngaus, [(0.0_dp, k=1, 2*nn)], ngp, xyg, sg, sn(:, 1:nn), ierr)
            gp_start(ie + 1) = gp_start(ie) + ngp
         end do
         allocate (xygp(2, gp_start(m%nelem + 1) - 1), sig_gp(4, gp_start(m%nelem + 1) - 1), sig_nd(4, m%npoin))
      end if
      allocate (cnt(m%npoin))
      cnt = 0.0_dp
      sig_nd = 0.0_dp
      do ie = 1, m%nelem
         nn = m%nnode_e(ie)
         imat = m%matno(ie)
         elcod(:, 1:nn) = m%coord(:, m%lnods(1:nn, ie))
         do k = 1, nn
            eldis(2*k - 1:2*k) = disp(:, m%lnods(k, ie))
         end do
         call element_stresses(m%ntype, nn, elcod(:, 1:nn), m%mats(imat)%young, m%mats(imat)%poiss, &
                               m%ngaus, eldis(1:2*nn), ngp, xyg, sg, sn(:, 1:nn), ierr)
         if (ierr /= 0) then
            call status%set(STAT_JACOBIAN, 'element '//itoa(ie)//' (stress recovery): '//element_error(ierr))
            return
         end if
         xygp(:, gp_start(ie):gp_start(ie + 1) - 1) = xyg(:, 1:ngp)
         sig_gp(:, gp_start(ie):gp_start(ie + 1) - 1) = sg(:, 1:ngp)
         do k = 1, nn
            sig_nd(:, m%lnods(k, ie)) = sig_nd(:, m%lnods(k, ie)) + sn(:, k)
            cnt(m%lnods(k, ie)) = cnt(m%lnods(k, ie)) + 1.0_dp
         end do
      end do
      do k = 1, m%npoin
         if (cnt(k) > 0.0_dp) sig_nd(:, k) = sig_nd(:, k)/cnt(k)
      end do
   end subroutine recover_stresses
end module incremental
