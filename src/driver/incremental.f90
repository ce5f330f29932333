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
!! increment with new stiffnesses, solved for the correction).  Totals are sums
!! of increments (eqs. 3.34-3.36).  Stresses, reactions and the contact
!! quantities are written to the HDF5 file, which is flushed.
!!
!! A numerical failure stops the loop cleanly: every finished increment stays
!! in the result file, whose status attribute says what happened.
module incremental
   use kinds, only: dp, i8, stdout, stderr
   use errors, only: status_t, STAT_SINGULAR, STAT_INPUT, STAT_IO, STAT_JACOBIAN, STAT_NO_CONVERGENCE
   use strings, only: itoa, rtoa, strip_extension, basename
   use model, only: model_t, MAX_NODE, NTYPE_AXISYMMETRIC
   use dof_map, only: dof_map_t
   use equation_numbering, only: numbering_report_t, number_equations, write_numbering_report
   use linear_solver, only: linear_solver_t
   use solver_factory, only: create_solver
   use assembly, only: coupling_t, assemble_bodies, assemble_load_cases, &
                       subtract_prescribed, restrained_forces, element_error
   use solid2d, only: element_stresses, element_stiffness
   use quadrature, only: max_gp
   use contact_types, only: UPDATE_RETURN, contact_pair_t, MAX_PAIR_NODES, LAW_ROUGH, PAIR_RIGID
   use contact_algorithm, only: contact_state_t, contact_init, begin_increment, pair_matrix, &
                                evaluate_pairs, commit_increment, pair_force_vector, law_drift, check_invariants, &
                                augment_multipliers, pair_dofs, start_force_normal
   use contact_element, only: pair_stiffness
   use condensation, only: condensed_t
   use restraint_check, only: find_bodies
   use results_hdf5, only: results_file_t
   use version, only: K2D_VERSION
   use listing, only: list_header, list_method, list_input, list_step, list_progress_header, list_progress
   use records, only: step_record_t, body_fields_t, contact_fields_t, run_info_t, STEP_CONVERGED, STEP_UNSETTLED
   use contact_fields, only: build_contact_fields, pair_spacing
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

   !> What a run leaves in memory (used by the tests and the caller): the
   !! body fields of the last step (disp, react, sig_nd, sig_gp, xygp,
   !! gp_start), the committed contact states, what the run used, and the
   !! history of the steps' figures.
   type, extends(body_fields_t) :: run_result_t
      integer :: completed = 0                   !! increments finished
      type(contact_state_t) :: contact           !! committed contact states
      type(contact_fields_t) :: fields           !! contact fields of the last step (contact models)
      type(run_info_t) :: info                   !! what the run used (solver, caps, contact system)
      integer, allocatable :: iterations(:)      !! solves per increment
      integer, allocatable :: repeats(:)         !! repeats (mode changes) per increment
      real(dp), allocatable :: residual(:)       !! relative out-of-balance force after each increment
      real(dp), allocatable :: drift(:)          !! largest departure of F_n from its curve, relative
      real(dp), allocatable :: imbalance(:)      !! largest force imbalance of a body, relative
      integer, allocatable :: violations(:)      !! invariant violations per increment (SPEC §7)
      real(dp), allocatable :: penetration(:)    !! ideal contact: largest |u_n| (closed) or stick slip at the end
      integer, allocatable :: augmentations(:)   !! ideal contact: multiplier updates per increment
      character(len=:), allocatable :: results_path
      logical :: reported = .false.              !! a failure was already printed
      integer :: warnings = 0                    !! warnings printed about the method (closure, chatter)
   end type run_result_t

   !> Everything the increment loop works with.
   type :: analysis_t
      type(dof_map_t) :: map
      class(linear_solver_t), allocatable :: solver
      type(coupling_t) :: coup
      real(dp), allocatable :: fcase(:, :, :)      !! (2, npoin, ncase) forces at factor 1
      real(dp), allocatable :: ucase(:, :, :)      !! (2, npoin, ncase) prescribed displacements at factor 1
      logical, allocatable :: restrained(:, :)     !! (2, npoin)
      integer :: npair = 0
      integer :: nd = 4                            !! dofs of the largest pair (2 MAX_PAIR_NODES)
      integer, allocatable :: peq(:, :)            !! (nd, npair) equations of the pairs' dofs, 0 beyond 2 nn
      real(dp), allocatable :: kstore(:, :, :)     !! (nd, nd, npair) spring matrices of the current system
      real(dp), allocatable :: kref(:, :, :)       !! (nd, nd, npair) reference springs of the condensation
      integer :: maxrep = 30                       !! cap on solutions of one increment
      logical :: has_contact = .false.
      logical :: returning = .false.               !! RETURN update (Newton)
      logical :: modified = .false.                !! modified Newton: stiffness kept within an increment
      logical :: condensed = .false.               !! bodies condensed onto the contact equations
      logical :: system_current = .false.          !! the solver holds the factors of the current system
      type(condensed_t) :: cond
      real(dp), allocatable :: spacing(:)          !! (npair) distance to the nearest other pair
      logical :: warned_closure = .false.
      logical :: warned_chatter = .false.
   end type analysis_t

   !> Outcome of one attempt at an increment (nothing committed yet).
   type :: attempt_t
      real(dp), allocatable :: du(:, :)            !! displacement increment
      real(dp), allocatable :: carry(:)            !! out-of-balance force left, free equations
      integer :: solutions = 0                     !! linear solutions
      integer :: repeats = 0                       !! solutions caused by mode changes
      logical :: converged = .false.
      logical :: changing = .false.                !! springs still changed their modes at the end
      real(dp) :: rnorm = 0.0_dp                   !! relative out-of-balance force
   end type attempt_t

contains

   !> Solve the model through its load history.
   subroutine run_analysis(m, opts, res, status)
      type(model_t), intent(inout) :: m
      type(run_options_t), intent(in) :: opts
      type(run_result_t), intent(out) :: res
      type(status_t), intent(inout) :: status
      type(analysis_t) :: an
      type(attempt_t) :: att
      type(results_file_t) :: rf
      type(numbering_report_t) :: numbering
      real(dp), allocatable :: fext(:, :), fext_new(:, :), carry(:), dlam(:), ve_old(:)
      integer, allocatable :: body(:)
      integer :: inc, lu, ios, nbody, nstep, cuts, ic, j
      integer(i8) :: t0, rate
      character(len=256) :: iomsg
      character(len=:), allocatable :: solver_name, lis_path, lis_level
      logical :: have_lis, first
      real(dp) :: frac, step, s, force_scale, gap_tol
      type(step_record_t) :: srec

      call system_clock(t0, rate)
      call complete_model(m)
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

      call set_up(m, solver_name, an, numbering, status)
      if (.not. status%ok()) return

      allocate (res%disp(2, m%npoin), res%react(2, m%npoin), fext(2, m%npoin), fext_new(2, m%npoin), &
                carry(an%map%neq), dlam(m%ncase), ve_old(an%npair))
      allocate (res%iterations(0), res%repeats(0), res%residual(0), res%drift(0), res%imbalance(0), &
                res%violations(0), res%penetration(0), res%augmentations(0))
      res%disp = 0.0_dp
      res%react = 0.0_dp
      fext = 0.0_dp
      carry = 0.0_dp
      force_scale = tiny(1.0_dp)

      ! ---- contact: initial states, start pressure of eq. (4.1)
      gap_tol = m%contact%opts%gap_tol
      if (gap_tol < 0.0_dp) gap_tol = 1.0e-9_dp*model_size(m)
      call contact_init(m%contact, gap_tol, res%contact)
      ! the cap on solutions per increment: CONTACT REPEATS, or 30 for the rough
      ! springs and 100 when the augmented Lagrangian of an ideal interface has
      ! to converge too
      an%maxrep = max(1, m%contact%opts%max_repeats)
      if (res%contact%has_ideal .and. .not. m%contact%opts%repeats_given) an%maxrep = 100
      allocate (body(m%npoin))
      call find_bodies(m, reshape([integer ::], [2, 0]), body, nbody)
      ! a rigid body's reference node belongs to no element: a body of its own
      do j = 1, an%npair
         if (m%contact%pairs(j)%kind /= PAIR_RIGID) cycle
         if (body(m%contact%pairs(j)%node_b) > 0) cycle
         nbody = nbody + 1
         body(m%contact%pairs(j)%node_b) = nbody
      end do
      if (an%has_contact .and. res%contact%has_rough) then
         call start_pressure(m, an%fcase, m%lambda(:, 1) - m%lambda(:, 0), res%contact, status)
         if (.not. status%ok()) return
      end if
      if (an%has_contact) then
         if (an%condensed) call set_up_condensation(m, an, status)
         if (.not. status%ok()) return
      end if

      ! ---- stress recovery layout (Gauss points are fixed)
      call recover_stresses(m, res%disp, res%gp_start, res%xygp, res%sig_gp, res%sig_nd, status)
      if (.not. status%ok()) return
      res%restrained = an%restrained
      call run_information(m, an, res%info)

      ! ---- listing, then the result file (nothing is left behind if either fails)
      have_lis = lis_level /= 'NONE'
      lu = 0
      if (have_lis) then
         open (newunit=lu, file=lis_path, status='replace', action='write', iostat=ios, iomsg=iomsg)
         if (ios /= 0) then
            call status%set(STAT_INPUT, 'cannot open the listing file '//lis_path//': '//trim(iomsg))
            return
         end if
         call list_header(lu, m, res%info)
         call write_numbering_report(lu, numbering)
         call list_method(lu, res%info)
         if (lis_level == 'FULL') call list_input(lu, m)
      end if
      call rf%create(res%results_path, m, res%body_fields_t, status)
      if (.not. status%ok()) then
         ! a result path that cannot be written is a command-line error
         status%code = STAT_INPUT
         call rf%close()
         if (have_lis) close (lu, status='delete')
         return
      end if
      call rf%write_run_info(res%info, status)
      if (an%has_contact .and. status%ok()) call rf%write_contact_definition(m%contact, res%info, status)
      if (.not. status%ok()) return
      if (.not. opts%quiet) then
         call list_header(stdout, m, res%info)
         call write_numbering_report(stdout, numbering)
         call list_method(stdout, res%info)
         write (stdout, '(a)') ' Results      : '//res%results_path
         if (have_lis) write (stdout, '(a)') ' Listing      : '//lis_path
         write (stdout, '(a)') repeat('-', 78)
         call list_progress_header(stdout, an%has_contact)
      end if

      ! ---- the loop over the deck's increments; with AUTOINC each may be cut
      !      into steps (halved when a step fails, doubled after easy ones)
      nstep = 0
      first = .true.
      step = 1.0_dp
      deck: do inc = 1, m%nincs
         frac = 0.0_dp
         if (.not. m%autoinc) step = 1.0_dp
         cuts = 0
         do while (frac < 1.0_dp - 1.0e-12_dp)
            s = min(step, 1.0_dp - frac)
            dlam = (m%lambda(:, inc) - m%lambda(:, inc - 1))*s
            fext_new = fext
            do ic = 1, m%ncase
               fext_new = fext_new + dlam(ic)*an%fcase(:, :, ic)
            end do
            if (first .and. an%has_contact .and. res%contact%has_rough .and. m%contact%opts%p_start <= 0.0_dp) then
               call start_pressure(m, an%fcase, dlam, res%contact, status)
               if (.not. status%ok()) exit deck
            end if
            call attempt_increment(an, m, res%contact, dlam, carry, fext_new, first, att, status)
            if (.not. m%autoinc) then
               if (.not. status%ok()) exit deck
               call failed_convergence(an, att, res%contact, nstep + 1, status)
               if (.not. status%ok()) exit deck
            else if (.not. status%ok() .or. .not. att%converged .or. res%contact%chatter) then
               ! cut the step and try again from the committed state
               if (s <= m%autoinc_min*(1.0_dp + 1.0e-9_dp)) then
                  if (status%ok()) call failed_convergence(an, att, res%contact, nstep + 1, status)
                  if (status%ok()) call status%set(STAT_NO_CONVERGENCE, 'contact states keep changing in increment '// &
                                                   itoa(nstep + 1)//' even at the smallest step')
                  status%message = status%message//' (automatic increments: smallest step '// &
                                   rtoa(m%autoinc_min)//' of deck increment '//itoa(inc)//' reached)'
                  exit deck
               end if
               status = status_t()
               step = max(0.5_dp*s, m%autoinc_min)
               cuts = cuts + 1
               if (.not. opts%quiet) write (stdout, '(a,i0,a,f9.6)') '      cut: deck increment ', inc, &
                  ', step fraction ', step
               cycle
            end if

            ! ---- the step is accepted: commit it
            nstep = nstep + 1
            frac = frac + s
            first = .false.
            fext = fext_new
            carry = att%carry
            ve_old = res%contact%s%ve
            if (an%has_contact) call commit_increment(m%contact, res%contact)
            res%disp = res%disp + att%du
            call record_step(res, att, an%has_contact, m, res%contact)
            if (an%has_contact) call method_warnings(an, m, res, nstep)
            srec = step_record_t(step=nstep, deck_increment=inc, fraction=frac, cuts=cuts, &
                                 lambda=m%lambda(:, inc - 1) + (m%lambda(:, inc) - m%lambda(:, inc - 1))*frac, &
                                 solutions=att%solutions, repeats=att%repeats, residual=res%residual(nstep), &
                                 drift=res%drift(nstep), penetration=res%penetration(nstep), &
                                 augmentations=res%augmentations(nstep), &
                                 status=merge(STEP_CONVERGED, STEP_UNSETTLED, att%converged), contact=an%has_contact, &
                                 ideal=res%contact%has_ideal, last=inc == m%nincs .and. frac >= 1.0_dp - 1.0e-12_dp)
            srec%written = srec%last .or. mod(nstep, m%results_every) == 0
            call finish_step(m, an, res, rf, lu, have_lis, lis_level, opts, body, nbody, fext, ve_old, force_scale, &
                             srec, t0, rate, status)
            if (.not. status%ok()) exit deck
            cuts = 0
            if (m%autoinc .and. att%solutions <= m%autoinc_easy .and. .not. res%contact%chatter) &
               step = min(1.0_dp, 2.0_dp*step)
         end do
      end do deck

      if (status%ok()) then
         call rf%set_status('completed')
         if (.not. opts%quiet) then
            write (stdout, '(a)') repeat('-', 78)
            write (stdout, '(a)') ' Completed '//itoa(res%completed)//' increment(s); results in '//res%results_path
         end if
         ! the drift of the paper's explicit scheme (SPEC §4.2), so that it is never silent
         if (an%has_contact .and. .not. an%returning .and. res%completed > 0 .and. .not. opts%quiet) then
            if (maxval(res%drift) > 0.05_dp) write (stderr, '(a)') 'kontakt2d: note: the incremental scheme '// &
               'left normal spring forces up to '//rtoa(100.0_dp*maxval(res%drift), '(f6.1)')//' % (increment '// &
               itoa(maxloc(res%drift, 1))//') off the interface law (attribute law_drift); more increments '// &
               'reduce this, CONTACT SCHEME NEWTON removes it'
         end if
      else
         call rf%set_status('failed at increment '//itoa(res%completed + 1)//': '//status%message)
         res%reported = .true.
         write (stderr, '(a)') 'kontakt2d: increment '//itoa(res%completed + 1)//' failed: '//status%message
         if (m%results_every > 1) then
            write (stderr, '(a)') 'kontakt2d: '//itoa(res%completed)//' increment(s) completed; '// &
               res%results_path//' keeps one in '//itoa(m%results_every)//' (OPTIONS RESULTS), the last '// &
               'of them increment '//itoa((res%completed/m%results_every)*m%results_every)
         else
            write (stderr, '(a)') 'kontakt2d: '//itoa(res%completed)//' completed increment(s) are kept in '// &
               res%results_path
         end if
      end if
      call rf%close()
      if (have_lis) close (lu)
      call an%solver%free()
   end subroutine run_analysis

   !> Equations, solver, K_AB and the load vectors; the contact pairs' equations.
   subroutine set_up(m, solver_name, an, numbering, status)
      type(model_t), intent(inout) :: m
      character(len=*), intent(in) :: solver_name
      type(analysis_t), intent(inout) :: an
      type(numbering_report_t), intent(out) :: numbering
      type(status_t), intent(inout) :: status
      integer, allocatable :: xadj(:), adjncy(:), links(:, :)
      integer :: j, k, ip, nlink

      an%has_contact = m%contact%active
      an%npair = size(m%contact%pairs)
      an%returning = m%contact%opts%update == UPDATE_RETURN
      an%modified = an%returning .and. m%contact%opts%modified

      ! equations (ties share equations; RCM order for the skyline solver), pattern
      ! with every contact pair, K_AB
      ! all nodes of a pair couple: node a with its master side (node b, the nodes
      ! of B under its tributary zone, or a rigid body's reference node), and
      ! those master nodes with each other
      nlink = 0
      do j = 1, an%npair
         nlink = nlink + (m%contact%pairs(j)%nn*(m%contact%pairs(j)%nn - 1))/2
      end do
      allocate (links(2, nlink))
      nlink = 0
      do j = 1, an%npair
         do k = 2, m%contact%pairs(j)%nn
            do ip = 1, k - 1
               nlink = nlink + 1
               links(:, nlink) = [m%contact%pairs(j)%nodes(ip), m%contact%pairs(j)%nodes(k)]
            end do
         end do
      end do
      call number_equations(m, solver_name, links, an%map, xadj, adjncy, numbering, status, ties=m%ties)
      if (.not. status%ok()) return
      call create_solver(solver_name, an%solver, status)
      if (.not. status%ok()) then
         status%code = STAT_INPUT
         return
      end if
      call an%solver%analyse(an%map%neq, xadj, adjncy, status)
      if (.not. status%ok()) return
      call an%solver%zero()
      call assemble_bodies(m, an%map, an%solver, an%coup, status)
      if (.not. status%ok()) return
      call an%solver%store_base()
      call assemble_load_cases(m, an%fcase, an%ucase, status)
      if (.not. status%ok()) return
      allocate (an%restrained(2, m%npoin))
      an%restrained = an%map%id < 0
      an%nd = 2*MAX_PAIR_NODES
      allocate (an%peq(an%nd, an%npair), an%kstore(an%nd, an%nd, an%npair))
      an%kstore = 0.0_dp
      an%peq = 0
      do j = 1, an%npair
         do k = 1, m%contact%pairs(j)%nn
            an%peq(2*k - 1:2*k, j) = an%map%id(:, m%contact%pairs(j)%nodes(k))
         end do
      end do
      an%spacing = pair_spacing(m%contact%pairs)
      an%condensed = .false.
      if (an%has_contact) then
         select case (m%condense)
         case ('ON')
            an%condensed = .true.
         case ('AUTO')
            an%condensed = count_contact_equations(an) <= 1500
         end select
      end if
   end subroutine set_up

   !> Number of distinct free equations of the contact pairs.
   integer function count_contact_equations(an) result(nc)
      type(analysis_t), intent(in) :: an
      integer, allocatable :: c(:)
      call contact_equations(an, c)
      nc = size(c)
   end function count_contact_equations

   !> The distinct free equations of the contact pairs, sorted.
   subroutine contact_equations(an, c)
      type(analysis_t), intent(in) :: an
      integer, allocatable, intent(out) :: c(:)
      logical, allocatable :: mark(:)
      integer :: j, k
      allocate (mark(an%map%neq))
      mark = .false.
      do j = 1, an%npair
         do k = 1, an%nd
            if (an%peq(k, j) > 0) mark(an%peq(k, j)) = .true.
         end do
      end do
      c = pack([(k, k=1, an%map%neq)], mark)
   end subroutine contact_equations

   !> Factorize B = K_AB + K_ref once and condense it onto the contact
   !! equations.  K_ref gives every pair a spring of the bodies' own stiffness
   !! scale in both directions, so that B is regular even where the springs are
   !! the only support of a body; each solve then uses the change K_c - K_ref,
   !! which acts on the contact equations only.
   subroutine set_up_condensation(m, an, status)
      type(model_t), intent(in) :: m
      type(analysis_t), intent(inout) :: an
      type(status_t), intent(inout) :: status
      integer, allocatable :: c(:)
      real(dp), allocatable :: diag(:)
      real(dp) :: kref
      integer :: j, k, n
      ! the bodies' stiffness scale at each contact equation: K_AB's diagonal
      allocate (diag(an%map%neq))
      call an%solver%restore_base()
      call body_diagonal(m, an, diag)
      allocate (an%kref(an%nd, an%nd, an%npair))
      an%kref = 0.0_dp
      do j = 1, an%npair
         ! the smallest diagonal of the pair's free equations: a tied or very stiff
         ! side would otherwise give a reference spring far stiffer than any
         ! contact spring, and K_c - K_ref would lose digits to cancellation
         kref = huge(1.0_dp)
         n = 0
         ! (a rigid body's reference node has no elements: zero diagonal, skipped;
         ! its reference springs then come from the deformable side alone)
         do k = 1, an%nd
            if (an%peq(k, j) <= 0) cycle
            if (diag(an%peq(k, j)) <= 0.0_dp) cycle
            kref = min(kref, diag(an%peq(k, j)))
            n = n + 1
         end do
         if (n == 0) kref = 1.0_dp
         kref = 0.1_dp*kref
         associate (pr => m%contact%pairs(j))
            call pair_stiffness(pr%t, pr%n, pr%nn, pr%w, kref, kref, an%kref(:, :, j))
         end associate
         call an%solver%add_element(an%peq(:, j), an%kref(:, :, j))
      end do
      call an%solver%factorize(status)
      if (.not. status%ok()) then
         status%message = 'condensation: the bodies with reference springs are singular ('//status%message// &
                          '); check the restraints'
         return
      end if
      call contact_equations(an, c)
      call an%cond%setup(an%solver, an%map%neq, c, status)
   end subroutine set_up_condensation

   !> Diagonal of K_AB on the free equations (element by element).
   subroutine body_diagonal(m, an, diag)
      type(model_t), intent(in) :: m
      type(analysis_t), intent(in) :: an
      real(dp), intent(out) :: diag(:)
      real(dp) :: estif(2*MAX_NODE, 2*MAX_NODE), elcod(2, MAX_NODE)
      integer :: ie, nn, ierr, k, ieq, imat
      diag = 0.0_dp
      do ie = 1, m%nelem
         nn = m%nnode_e(ie)
         imat = m%matno(ie)
         elcod(:, 1:nn) = m%coord(:, m%lnods(1:nn, ie))
         call element_stiffness(m%ntype, nn, elcod(:, 1:nn), m%mats(imat)%young, m%mats(imat)%poiss, &
                                m%mats(imat)%thick, m%ngaus, estif(1:2*nn, 1:2*nn), ierr)
         do k = 1, 2*nn
            ieq = an%map%id(mod(k - 1, 2) + 1, m%lnods((k + 1)/2, ie))
            if (ieq > 0) diag(ieq) = diag(ieq) + estif(k, k)
         end do
      end do
   end subroutine body_diagonal

   !> One attempt at an increment of the load factors dlam from the committed
   !! state: solve, check the springs, repeat until they keep their modes and
   !! balance (or the cap).  Nothing is committed here.
   subroutine attempt_increment(an, m, st, dlam, carry, fext_new, first, att, status)
      type(analysis_t), intent(inout) :: an
      type(model_t), intent(in) :: m
      type(contact_state_t), intent(inout) :: st
      real(dp), intent(in) :: dlam(:), carry(:), fext_new(:, :)
      logical, intent(in) :: first
      type(attempt_t), intent(inout) :: att
      type(status_t), intent(inout) :: status
      real(dp), allocatable :: rhs(:), ddu(:, :), rvec(:, :), rpred(:, :), w1(:), wc(:), dvc(:), zc(:), rsum(:)
      logical, allocatable :: changed(:)
      integer :: ip, idof, ic, j, iter, maxit, k
      real(dp) :: fscale, dnorm
      logical :: need_matrix, done, again

      allocate (rhs(an%map%neq), ddu(2, m%npoin), rvec(an%nd, an%npair), rpred(an%nd, an%npair), changed(an%npair))
      rvec = 0.0_dp
      rpred = 0.0_dp
      if (.not. allocated(att%du)) allocate (att%du(2, m%npoin), att%carry(an%map%neq))
      att%du = 0.0_dp
      att%solutions = 0
      att%repeats = 0
      att%converged = .false.
      att%changing = .false.
      att%rnorm = 0.0_dp
      st%chatter = .false.
      rhs = carry
      do ic = 1, m%ncase
         where (an%restrained) att%du = att%du + dlam(ic)*an%ucase(:, :, ic)
      end do
      do ip = 1, m%npoin
         do idof = 1, 2
            if (an%map%id(idof, ip) > 0) rhs(an%map%id(idof, ip)) = rhs(an%map%id(idof, ip)) + &
                                                                   sum(dlam*an%fcase(idof, ip, :))
         end do
      end do
      call subtract_prescribed(an%coup, an%map, att%du, rhs)
      fscale = max(maxval([0.0_dp, abs(rhs)]), maxval(abs(fext_new)), 1.0e-300_dp)

      ! spring forces and modes at the start of the increment
      if (an%has_contact) then
         call begin_increment(m%contact, st, first)
         do j = 1, an%npair
            call pair_force_vector(m%contact, j, st%s(j)%fn, st%s(j)%ft, rpred(:, j))
            call pair_force_vector(m%contact, j, start_force_normal(m%contact, st, j), st%s(j)%ft, rvec(:, j))
            k = 2*m%contact%pairs(j)%nn
            ! (an ideal pair closed across a gap: the out-of-balance force of its penalty term)
            call scatter_free(an%peq(1:k, j), rpred(1:k, j) - rvec(1:k, j), rhs)
         end do
         rpred = 0.0_dp
      end if
      if (an%condensed) then
         allocate (wc(an%cond%nc), dvc(an%cond%nc), zc(an%cond%nc), rsum(an%cond%nc))
         zc = 0.0_dp
         rsum = 0.0_dp
      end if

      ddu = att%du       ! first solve: prescribed increments at the restrained dofs
      need_matrix = an%has_contact .or. .not. an%system_current
      maxit = 1
      if (an%has_contact) maxit = an%maxrep
      do iter = 1, maxit
         if (need_matrix) then
            call set_system(an, m, st, status)
            if (.not. status%ok()) return
         end if
         if (iter == 1) then
            call subtract_contact_prescribed(an%peq, an%kstore, m%contact%pairs, ddu, rhs)
            ! an increment driven only through springs of prescribed nodes (a rigid
            ! body's reference node belongs to no element) has no other force to
            ! measure its out-of-balance force against
            if (fscale <= 1.0e-300_dp .and. an%map%neq > 0) fscale = max(maxval(abs(rhs)), 1.0e-300_dp)
         end if
         if (an%condensed) then
            ! (B + dK) dv = b with dK = K_c - K_ref on the contact equations only
            if (iter == 1) then
               w1 = rhs
               call an%solver%solve(w1, status)
               if (.not. status%ok()) return
               wc = w1(an%cond%ceq)
            else
               wc = matmul(an%cond%g, rhs(an%cond%ceq))
               rsum = rsum + rhs(an%cond%ceq)
            end if
            call an%cond%solve_c(wc, dvc, status)
            if (.not. status%ok()) then
               call describe_singular(an, status)
               return
            end if
            zc = zc + matmul(an%cond%kcc, dvc)
            ! the contact part of the solution at the pairs' nodes (only these are needed now)
            do j = 1, an%npair
               do idof = 1, 2*m%contact%pairs(j)%nn
                  if (an%peq(idof, j) <= 0) cycle
                  ip = m%contact%pairs(j)%nodes((idof + 1)/2)
                  ddu(mod(idof - 1, 2) + 1, ip) = dvc(an%cond%pos(an%peq(idof, j)))
               end do
            end do
         else
            call an%solver%solve(rhs, status)
            if (.not. status%ok()) return
            do ip = 1, m%npoin
               do idof = 1, 2
                  if (an%map%id(idof, ip) > 0) ddu(idof, ip) = rhs(an%map%id(idof, ip))
               end do
            end do
         end if
         att%solutions = iter
         att%du = att%du + merge(0.0_dp, ddu, an%restrained)
         if (.not. an%has_contact) then
            att%converged = .true.
            rhs = 0.0_dp         ! it held the solution: no out-of-balance force is left
            exit
         end if
         ! predicted spring forces (the linearisation the solve used) ...
         do j = 1, an%npair
            k = 2*m%contact%pairs(j)%nn
            rpred(1:k, j) = rvec(1:k, j) + matmul(an%kstore(1:k, 1:k, j), pair_values(ddu, m%contact%pairs(j), k))
         end do
         dnorm = maxval(abs(merge(0.0_dp, ddu, an%restrained)))/max(maxval(abs(att%du)), tiny(1.0_dp))
         ddu = 0.0_dp
         ! ... against the actual ones, after the mode checks
         call update_modes(again)
         if (again) cycle
         if (att%rnorm <= m%contact%opts%tol_residual .and. &
             (.not. an%returning .or. dnorm <= m%contact%opts%tol_displacement .or. iter == 1)) then
            if (.not. st%has_ideal) then
               att%converged = .true.
               exit
            end if
            ! ideal contact: the modes hold and the bodies balance the forces of the
            ! current multipliers; converged when the penetrations are within
            ! tolerance, else an Uzawa update and the forces of the new multipliers
            ! drive the next solution
            call augment_multipliers(m%contact, st, done)
            if (done) then
               att%converged = .true.
               exit
            end if
            call update_modes(again)
            if (again) cycle
         end if
         need_matrix = an%returning .and. .not. an%modified
      end do
      att%carry = rhs

      ! condensed path: the full-length displacement increment from one more solve
      if (an%condensed .and. an%has_contact) then
         rhs = 0.0_dp
         rhs(an%cond%ceq) = rsum - zc
         call an%solver%solve(rhs, status)
         if (.not. status%ok()) return
         rhs = w1 + rhs
         do ip = 1, m%npoin
            do idof = 1, 2
               if (an%map%id(idof, ip) > 0) att%du(idof, ip) = rhs(an%map%id(idof, ip))
            end do
         end do
      end if
   contains
      !> Modes and forces of the pairs for the current displacements, and the
      !! out-of-balance force; again: some mode changed, so the increment is
      !! repeated with a new matrix.
      subroutine update_modes(again)
         logical, intent(out) :: again
         call evaluate_pairs(m%contact, st, att%du, changed, first)
         call residual_forces()
         att%changing = any(changed)
         again = att%changing
         if (again) then
            att%repeats = att%repeats + 1
            need_matrix = .true.
         end if
      end subroutine update_modes

      !> Internal-force vectors of the pairs for their current forces, and the
      !! out-of-balance force: the forces the solve predicted minus these.
      subroutine residual_forces()
         integer :: jp, nv
         do jp = 1, an%npair
            call pair_force_vector(m%contact, jp, st%fn(jp), st%ft(jp), rvec(:, jp))
         end do
         rhs = 0.0_dp
         do jp = 1, an%npair
            nv = 2*m%contact%pairs(jp)%nn
            call scatter_free(an%peq(1:nv, jp), rpred(1:nv, jp) - rvec(1:nv, jp), rhs)
         end do
         att%rnorm = 0.0_dp
         if (an%map%neq > 0) att%rnorm = maxval(abs(rhs))/fscale
      end subroutine residual_forces
   end subroutine attempt_increment

   !> Put the springs of the current modes into the system: refactorize
   !! K_AB + K_c, or, when condensed, assemble K_c - K_ref on the contact equations.
   subroutine set_system(an, m, st, status)
      type(analysis_t), intent(inout) :: an
      type(model_t), intent(in) :: m
      type(contact_state_t), intent(in) :: st
      type(status_t), intent(inout) :: status
      integer :: j
      do j = 1, an%npair
         call pair_matrix(m%contact, st, j, an%kstore(:, :, j))
      end do
      if (an%condensed) then
         call an%cond%zero_springs()
         do j = 1, an%npair
            call an%cond%add_spring(an%peq(:, j), an%kstore(:, :, j) - an%kref(:, :, j))
         end do
         return
      end if
      call an%solver%restore_base()
      do j = 1, an%npair
         call an%solver%add_element(an%peq(:, j), an%kstore(:, :, j))
      end do
      call an%solver%factorize(status)
      an%system_current = status%ok()
      if (.not. status%ok()) call describe_singular(an, status)
   end subroutine set_system

   !> Name the node and dof of a singular equation in the message.
   subroutine describe_singular(an, status)
      type(analysis_t), intent(in) :: an
      type(status_t), intent(inout) :: status
      integer :: ieq, k
      character(len=:), allocatable :: detail
      if (status%code /= STAT_SINGULAR) return
      ieq = 0
      if (an%condensed) then
         k = index(status%message, 'contact equation ')
         if (k > 0) read (status%message(k + 17:), *) ieq
      else
         ieq = an%solver%failed_equation()
      end if
      if (ieq <= 0) return
      ! keep the solver's pivot figures, name the node and dof instead of the equation
      k = index(status%message, ': ')
      detail = status%message(k + 1:)
      if (k > 0) detail = status%message(k + 2:)
      status%message = 'singular or unrestrained model at '//an%map%describe(ieq)//': '//detail
      if (an%has_contact) status%message = status%message//'; a body held only by contact springs '// &
                                           'has no support once they open (normal) or slip (tangential)'
   end subroutine describe_singular

   !> An attempt that ended without convergence: a RETURN increment out of
   !! balance, or springs still changing their modes, is a failure; an EXPLICIT
   !! increment whose slip forces have not settled is accepted (its
   !! out-of-balance force is carried into the next increment).
   subroutine failed_convergence(an, att, st, inc, status)
      type(analysis_t), intent(in) :: an
      type(attempt_t), intent(in) :: att
      type(contact_state_t), intent(in) :: st
      integer, intent(in) :: inc
      type(status_t), intent(inout) :: status
      if (.not. an%has_contact .or. att%converged) return
      if (att%changing .or. st%chatter) then
         call status%set(STAT_NO_CONVERGENCE, 'no convergence in increment '//itoa(inc)//' after '// &
                         itoa(att%solutions)//' solutions (contact states keep changing); '// &
                         'reduce the increment size, raise CONTACT REPEATS or use OPTIONS AUTOINC')
      else if (st%has_ideal .and. att%rnorm <= 1.0e-8_dp) then
         call status%set(STAT_NO_CONVERGENCE, 'no convergence in increment '//itoa(inc)//' after '// &
                         itoa(att%solutions)//' solutions: ideal contact still penetrates or slips by '// &
                         rtoa(st%violation)//' > the tolerance '//rtoa(st%tol_pen)//' after '// &
                         itoa(st%augmentations)//' multiplier updates; raise CONTACT REPEATS or the AUGMENTED '// &
                         'factor, or use OPTIONS AUTOINC')
      else if (an%returning .or. st%has_ideal) then
         call status%set(STAT_NO_CONVERGENCE, 'no convergence in increment '//itoa(inc)//' after '// &
                         itoa(att%solutions)//' solutions (relative out-of-balance force '// &
                         rtoa(att%rnorm)//'); reduce the increment size, raise CONTACT REPEATS or use '// &
                         'OPTIONS AUTOINC')
      end if
   end subroutine failed_convergence

   !> Warning when the method is used outside its comfort zone (once per
   !! run): a tangential relative displacement above 10 % of the pair spacing
   !! (node-to-node pairs assume small sliding: the partners must stay
   !! opposite each other; very soft roughness or a large tangential load
   !! breaks that).
   subroutine method_warnings(an, m, res, nstep)
      type(analysis_t), intent(inout) :: an
      type(model_t), intent(in) :: m
      type(run_result_t), intent(inout) :: res
      integer, intent(in) :: nstep
      integer :: j
      if (.not. an%warned_closure) then
         do j = 1, an%npair
            if (abs(res%contact%s(j)%ut) > 0.1_dp*an%spacing(j)) then
               an%warned_closure = .true.
               res%warnings = res%warnings + 1
               write (stderr, '(a)') 'kontakt2d: warning: increment '//itoa(nstep)//': pair '//itoa(j)// &
                  ' has slid '//rtoa(abs(res%contact%s(j)%ut))//', more than 10 % of the pair spacing ('// &
                  rtoa(an%spacing(j))//'): node-to-node contact assumes small sliding (the partners '// &
                  'must stay opposite each other); refine the contact mesh or use stiffer roughness data'
               exit
            end if
         end do
      end if
      if (.not. an%warned_chatter .and. res%contact%chatter) then
         an%warned_chatter = .true.
         res%warnings = res%warnings + 1
         write (stderr, '(a)') 'kontakt2d: warning: increment '//itoa(nstep)//': contact springs kept switching '// &
            'their states (chatter); their states were frozen after '//itoa(6)//' changes and the increment '// &
            'accepted; use smaller increments or OPTIONS AUTOINC'
      end if
      associate (unused => m)
      end associate
   end subroutine method_warnings

   !> Append the figures of an accepted step.
   subroutine record_step(res, att, has_contact, m, st)
      type(run_result_t), intent(inout) :: res
      type(attempt_t), intent(in) :: att
      logical, intent(in) :: has_contact
      type(model_t), intent(in) :: m
      type(contact_state_t), intent(in) :: st
      res%iterations = [res%iterations, att%solutions]
      res%penetration = [res%penetration, st%violation]
      res%augmentations = [res%augmentations, st%augmentations]
      res%repeats = [res%repeats, att%repeats]
      res%residual = [res%residual, merge(att%rnorm, 0.0_dp, has_contact)]
      if (has_contact) then
         res%drift = [res%drift, law_drift(m%contact, st)]
      else
         res%drift = [res%drift, 0.0_dp]
      end if
   end subroutine record_step

   !> Post-processing, checks, output and progress of an accepted step.
   subroutine finish_step(m, an, res, rf, lu, have_lis, lis_level, opts, body, nbody, fext, ve_old, force_scale, &
                          srec, t0, rate, status)
      type(model_t), intent(in) :: m
      type(analysis_t), intent(in) :: an
      type(run_result_t), intent(inout) :: res
      type(results_file_t), intent(inout) :: rf
      integer, intent(in) :: lu
      logical, intent(in) :: have_lis
      character(len=*), intent(in) :: lis_level
      type(run_options_t), intent(in) :: opts
      integer, intent(in) :: body(:), nbody
      real(dp), intent(in) :: fext(:, :), ve_old(:)
      real(dp), intent(inout) :: force_scale
      type(step_record_t), intent(inout) :: srec
      integer(i8), intent(in) :: t0, rate
      type(status_t), intent(inout) :: status
      real(dp), allocatable :: fr(:, :), fsp(:, :)
      real(dp) :: r(2*MAX_PAIR_NODES), imb
      integer :: j, k, nbad, nstep
      integer(i8) :: t1
      character(len=:), allocatable :: imsg

      nstep = srec%step
      call recover_stresses(m, res%disp, res%gp_start, res%xygp, res%sig_gp, res%sig_nd, status)
      if (.not. status%ok()) return
      allocate (fr(2, m%npoin), fsp(2, m%npoin))
      call restrained_forces(an%coup, an%map, res%disp, fr)
      fsp = 0.0_dp
      do j = 1, an%npair
         call pair_force_vector(m%contact, j, res%contact%s(j)%fn, res%contact%s(j)%ft, r)
         do k = 1, m%contact%pairs(j)%nn
            fsp(:, m%contact%pairs(j)%nodes(k)) = fsp(:, m%contact%pairs(j)%nodes(k)) + r(2*k - 1:2*k)
         end do
      end do
      res%react = 0.0_dp
      where (an%restrained) res%react = fr + fsp - fext

      ! invariants (SPEC §7): every body in equilibrium under loads, reactions
      ! and spring forces; no tension; |F_T| <= mu F_n; v_e non-decreasing
      force_scale = max(force_scale, maxval(abs(fext)), maxval(abs(res%react)), maxval(abs(fsp)))
      imb = body_imbalance(body, nbody, fext + res%react - fsp, force_scale, m%ntype == NTYPE_AXISYMMETRIC)
      nbad = 0
      imsg = ''
      if (an%has_contact) call check_invariants(res%contact, ve_old, nbad, imsg)
      if (imb > 1.0e-8_dp) then
         nbad = nbad + 1
         imsg = 'a body is out of equilibrium by '//rtoa(imb)//' of the load'
      end if
      res%imbalance = [res%imbalance, imb]
      res%violations = [res%violations, nbad]
      if (nbad > 0) write (stderr, '(a)') 'kontakt2d: warning: increment '//itoa(nstep)//': '//itoa(nbad)// &
         ' invariant violation(s): '//imsg
      srec%imbalance = imb
      srec%violations = nbad
      if (an%has_contact) call build_contact_fields(m%contact, res%contact, res%fields)

      ! OPTIONS RESULTS n: only every n-th step and the last go into the result file
      if (srec%written) then
         call rf%write_increment(srec, res%body_fields_t, status, res%fields)
         if (.not. status%ok()) return
      end if
      res%completed = nstep
      if (have_lis .and. (lis_level == 'FULL' .or. srec%last)) call list_step(lu, m, srec, res%body_fields_t, res%fields)
      call system_clock(t1)
      if (.not. opts%quiet) then
         call list_progress(stdout, srec, res%body_fields_t, real(t1 - t0, dp)/real(rate, dp), res%fields)
         flush (stdout)
      end if
   end subroutine finish_step

   !> What the run uses, for the headers and the result file.
   subroutine run_information(m, an, info)
      type(model_t), intent(in) :: m
      type(analysis_t), intent(in) :: an
      type(run_info_t), intent(out) :: info
      info%solver = an%solver%name()
      info%neq = an%map%neq
      info%nres = an%map%nres
      info%npair = an%npair
      info%system = ''
      info%returning = an%returning
      info%modified = an%modified
      if (an%condensed) info%system = 'Condensed    : bodies condensed onto '//itoa(an%cond%nc)// &
                                      ' contact equations (one factorization of the bodies)'
      info%condensed = an%condensed
      info%max_repeats = an%maxrep
      info%autoinc = m%autoinc
      info%autoinc_min = m%autoinc_min
      info%autoinc_easy = m%autoinc_easy
   end subroutine run_information

   !> Largest |sum of the forces on a body| relative to the force scale of the run.
   !! In axisymmetry only the axial resultant must vanish: the radial ring forces
   !! of a body in equilibrium do not add up to zero (its hoop stresses carry them).
   pure real(dp) function body_imbalance(body, nbody, f, scale, axisymmetric) result(worst)
      integer, intent(in) :: body(:), nbody
      real(dp), intent(in) :: f(:, :)        !! (2, npoin) external + reactions - spring internal forces
      real(dp), intent(in) :: scale          !! largest nodal force seen so far
      logical, intent(in) :: axisymmetric    !! check the axial (z) resultant only
      real(dp) :: total(2, max(nbody, 1))
      integer :: ip
      total = 0.0_dp
      do ip = 1, size(body)
         if (body(ip) > 0) total(:, body(ip)) = total(:, body(ip)) + f(:, ip)
      end do
      if (axisymmetric) then
         worst = maxval(abs(total(2, :)))/scale
      else
         worst = maxval(abs(total))/scale
      end if
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
