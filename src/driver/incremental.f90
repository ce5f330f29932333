!> The incremental driver: owns the loop over load increments.
!!
!! Set-up: equation numbering (with ties), the equation graph including every
!! contact pair, symbolic analysis, K_AB assembled once (bodies are linear
!! elastic, small strain: eq. 4.12) and kept in the solver as its base matrix,
!! load vectors of every load case; then the contact system (contact_system_t,
!! chosen once by the factory: the full system or the bodies condensed onto
!! the contact equations) takes the solver over.
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
!! of increments (eqs. 3.34-3.36).  An accepted step fills the step record;
!! the assembly layer fills the body fields (stresses, reactions), the contact
!! layer the contact fields; run_report (io) writes them to the result file,
!! the listing and the terminal, and owns those outputs and their paths.
!!
!! A numerical failure stops the loop cleanly: every finished increment stays
!! in the result file, whose status attribute says what happened (a failure
!! at set-up, before the first increment, leaves the mesh and that status);
!! a non-finite number in a solution is such a failure.  A run whose steps
!! raise doubts (step_audit: frozen states, law drift, invariant violations)
!! ends "doubtful", naming them.  The model is read only: what the run used is
!! reported in the run information.
module incremental
   use kinds, only: dp, stderr
   use errors, only: status_t, STAT_INPUT, STAT_NO_CONVERGENCE
   use strings, only: itoa, rtoa
   use model, only: model_t, NTYPE_AXISYMMETRIC, complete_model, model_complete
   use records, only: step_record_t, contact_fields_t, run_info_t, run_doubts_t, STEP_CONVERGED, &
                      STEP_UNSETTLED, cycle_table_t
   use equation_numbering, only: numbering_report_t, number_equations
   use solver_factory, only: create_solver, plan_run
   use contact_system, only: contact_equations
   use contact_system_factory, only: create_contact_system, contact_system_kind
   use run_plan, only: run_plan_t, CHOICE_AUTOMATIC, SCHEME_INCREMENTAL, SCHEME_MODIFIED, &
         CONDENSE_OFF
   use assembly, only: assemble_bodies, assemble_load_cases
   use contact_assembly, only: pair_links, spring_nodal_forces
   use body_fields, only: recover_stresses, update_reactions, number_bodies, body_imbalance, &
                          stiffness_range, zero_fields, estimate_error
   use contact_algorithm, only: contact_state_t, commit_increment, law_drift, MAX_SWITCH, &
         tangential_drift
   use step_audit, only: check_finite_attempt, check_runaway, check_finite_step, audit_step, &
         note_doubts, doubt_summary, check_runaway_displacement, &
                         sliding_warning, run_history_t, IMBALANCE_NOT_COMPUTED, &
                         imbalance_limit
   use contact_start, only: init_contact_states, start_pressure
   use increment_attempt, only: analysis_t, attempt_t, attempt_failure, describe_singular
   use contact_fields, only: build_contact_fields, pair_spacing
   use contact_energy, only: energy_t, energy_init, energy_begin, energy_commit, energy_fields, &
         energy_cycles
   use run_report, only: run_report_t, run_end_t
   use pretension_section, only: pretension_links
   use pretension_assembly, only: assemble_pretension, pretension_nodal_forces, section_forces, &
         section_shortening
   use pretension_control, only: attempt_with_pretension
   use increment_predictor, only: PREDICT_MIN_PAIRS
   implicit none
   private
   public :: run_options_t, run_result_t, run_analysis

   !> Choices of the command line that override or complement the deck.
   type :: run_options_t
      character(len=:), allocatable :: results_path   !! HDF5 file ('' = <deck>.h5
                                                      !! in the working directory)
      character(len=:), allocatable :: listing_path   !! listing file ('' = <results>.lis)
      character(len=:), allocatable :: solver_name    !! '' = the deck's choice
      logical :: quiet = .false.                      !! no terminal output except errors
      !> models of at least this many contact pairs start an increment's Newton iteration from
      !! the last increment (increment_predictor; 0: every model, huge(1): none)
      integer :: predict_min_pairs = PREDICT_MIN_PAIRS
   end type run_options_t

   !> What a run leaves in memory (used by the tests and the caller): the
   !! body fields of the last step (disp, react, sig_nd, sig_gp, xygp,
   !! gp_start), the committed contact states and the contact fields, what the
   !! run used, and the history of the steps' figures (run_history_t:
   !! iterations, repeats, residual, drift, imbalance, violations, penetration,
   !! augmentations, one entry per step).
   type, extends(run_history_t) :: run_result_t
      integer :: completed = 0                   !! increments finished
      type(contact_state_t) :: contact           !! committed contact states
      type(contact_fields_t) :: fields           !! contact fields of the last step (contact models)
      type(run_info_t) :: info                   !! what the run used (solver, caps, contact system)
      character(len=:), allocatable :: results_path
      logical :: reported = .false.              !! a failure was already printed
      integer :: warnings = 0                    !! warnings printed about the method (sliding)
      type(run_doubts_t) :: doubts               !! doubtful steps: the run ends
                                                 !! doubtful (exit code 4)
      type(energy_t) :: energy                   !! energy dissipated by the contact
                                                 !! laws (contact_energy)
      type(cycle_table_t) :: cycles              !! the load cycles found in the
                                                 !! history, at the end of the run
   end type run_result_t

contains

   !> Solve the model through its load history.  A model built in code
   !! without the empty parts a deck has (contact, ties) is completed on a copy.
   subroutine run_analysis(m, opts, res, status)
      type(model_t), intent(in) :: m
      type(run_options_t), intent(in) :: opts
      type(run_result_t), intent(out) :: res
      type(status_t), intent(inout) :: status
      type(model_t) :: mc
      if (model_complete(m)) then
         call run_model(m, opts, res, status)
      else
         mc = m
         call complete_model(mc)
         call run_model(mc, opts, res, status)
      end if
   end subroutine run_analysis

   !> Set up, open the outputs, run the load history, close.
   subroutine run_model(m, opts, res, status)
      type(model_t), intent(in) :: m
      type(run_options_t), intent(in) :: opts
      type(run_result_t), intent(inout) :: res
      type(status_t), intent(inout) :: status
      type(analysis_t) :: an
      type(run_report_t) :: out                 !! every output of the run (module run_report)
      type(numbering_report_t) :: numbering
      type(status_t) :: ostat
      type(run_plan_t) :: plan
      character(len=:), allocatable :: solver_name

      call out%start(m%deck_file, m%listing_level, opts%quiet, opts%results_path, opts%listing_path)
      res%results_path = out%results_path()
      ! the run plan, resolved once: -s, else the deck's SOLVER, else (AUTO) from the model's size
      ! and contact; the order of the equations, the scheme (the contact system in set_up)
      if (allocated(opts%solver_name)) then
         call plan_run(m, opts%solver_name, plan, solver_name)
      else
         call plan_run(m, '', plan, solver_name)
      end if

      call set_up(m, solver_name, plan, an, numbering, status)
      if (plan%solver_choice == CHOICE_AUTOMATIC) then
         numbering%solver_choice = solver_name//', chosen automatically ('//plan%solver_reason//')'
      end if
      if (status%ok()) call start_run(m, plan, an, res, status)
      if (an%npair < opts%predict_min_pairs) an%pred%enabled = .false.
      if (status%ok()) then
         call out%open(m, numbering, res%info, res%body_fields_t, .false., status)
         if (status%ok()) then
            call solve_history(m, an, res, out, status)
            call close_outputs(m, res, out, status, .false.)
         end if
      else if (status%code /= STAT_INPUT) then
         ! a numerical failure before the first increment: the result file
         ! keeps the mesh and says why (the listing and terminal too)
         if (.not. allocated(numbering%method)) then
            numbering = numbering_report_t(method='NONE', reason='not reached')
         end if
         if (.not. allocated(res%info%solver)) res%info = &
               run_info_t(plan=plan, solver=solver_name, system='', &
                                       npair=an%npair, returning=an%returning, modified=an%modified)
         call zero_fields(m, res%body_fields_t)
         call out%open(m, numbering, res%info, res%body_fields_t, .true., ostat)
         if (ostat%ok()) call close_outputs(m, res, out, status, .true.)
      end if
      if (allocated(an%sys)) call an%sys%free()
      if (allocated(an%solver)) call an%solver%free()
   end subroutine run_model

   !> Equations, solver, K_AB and the load vectors; the contact pairs'
   !! equations; the choice of the contact system.
   subroutine set_up(m, solver_name, plan, an, numbering, status)
      type(model_t), intent(in) :: m
      character(len=*), intent(in) :: solver_name   !! the plan's solver as named (create_solver
                                                    !! refuses a bad one)
      type(run_plan_t), intent(inout) :: plan       !! gets its contact system
      type(analysis_t), intent(inout) :: an
      type(numbering_report_t), intent(out) :: numbering
      type(status_t), intent(inout) :: status
      integer, allocatable :: xadj(:), adjncy(:), links(:, :), plinks(:, :)

      an%npair = size(m%contact%pairs)
      an%has_contact = an%npair > 0
      an%returning = plan%scheme /= SCHEME_INCREMENTAL
      an%modified = plan%scheme == SCHEME_MODIFIED

      ! equations (ties share equations; RCM order for the skyline solver), pattern
      ! with every contact pair, K_AB
      call pair_links(m%contact%pairs, links)
      call pretension_links(m, plinks)
      links = reshape([links, plinks], [2, size(links, 2) + size(plinks, 2)])
      call number_equations(m, plan, links, an%map, xadj, adjncy, numbering, status, ties=m%ties)
      if (.not. status%ok()) return
      call create_solver(solver_name, an%solver, status)
      if (.not. status%ok()) then
         status%code = STAT_INPUT
         return
      end if
      call an%solver%analyse(an%map%neq, xadj, adjncy, status)
      if (.not. status%ok()) return
      call an%solver%zero()
      allocate (an%diag(an%map%neq), an%absrow(an%map%neq))
      call assemble_bodies(m, an%map, an%solver, an%coup, status, an%diag, an%absrow)
      if (.not. status%ok()) return
      call assemble_pretension(m, an%map, an%solver, an%pret, an%diag, an%absrow)
      call an%solver%store_base()
      call assemble_load_cases(m, an%fcase, an%ucase, status)
      if (.not. status%ok()) return
      allocate (an%restrained(2, m%npoin))
      an%restrained = an%map%id < 0
      call an%springs%init(an%map, m%contact%pairs)
      an%spacing = pair_spacing(m%contact%pairs, m%contact)
      ! pretension sections: the lock measures the section between solutions, so the full system
      if (an%pret%n > 0) plan%condense = CONDENSE_OFF
      if (an%has_contact) plan%contact_system = contact_system_kind(plan%condense, an%npair, &
                                                  size(contact_equations(an%springs%peq, &
                                                                         an%map%neq)), an%solver)
      call create_contact_system(plan%contact_system, an%sys)
   end subroutine set_up

   !> Initial contact states, the cap on solutions, the bodies, the start
   !! pressure, the contact system, the Gauss-point layout, the run information.
   subroutine start_run(m, plan, an, res, status)
      type(model_t), intent(in) :: m
      type(run_plan_t), intent(in) :: plan
      type(analysis_t), intent(inout) :: an
      type(run_result_t), intent(inout) :: res
      type(status_t), intent(inout) :: status
      call zero_fields(m, res%body_fields_t)
      call res%trim_history()
      call init_contact_states(m, res%contact)
      call energy_init(m%contact, res%contact, m%lambda(:, 0), res%energy)
      ! the cap on solutions per increment: CONTACT REPEATS, or 30 for the rough
      ! springs and 100 when the augmented Lagrangian of an ideal interface has
      ! to converge too
      an%maxrep = max(1, m%contact%opts%max_repeats)
      if (res%contact%has_ideal .and. .not. m%contact%opts%repeats_given) an%maxrep = 100
      call number_bodies(m, an%body, an%nbody)
      if (an%has_contact .and. res%contact%has_rough) then
         call start_pressure(m, an%fcase, m%lambda(:, 1) - m%lambda(:, 0), res%contact, status)
         if (.not. status%ok()) return
      end if
      ! K_AB out of the range of double precision (an overflowing modulus) is
      ! named, not called singular
      call stiffness_range(an%map, an%diag, status)
      if (.not. status%ok()) return
      ! the contact system takes the solver (K_AB) over
      call an%springs%reference_springs(m%contact%pairs, an%diag, an%kref)
      call an%sys%setup(an%solver, an%map, an%springs%peq, an%kref, status)
      if (.not. status%ok()) call stiffness_range(an%map, an%diag, status)
      if (.not. status%ok()) return
      ! the first iterate of an increment predicted from the last one (increment_predictor): the
      ! Newton return of rough pairs, without ideal pairs or pretension sections
      an%pred%enabled = an%has_contact .and. an%returning .and. res%contact%has_rough .and. &
                        .not. res%contact%has_ideal .and. an%pret%n == 0
      call an%pred%forget()
      ! stress recovery layout (Gauss points are fixed)
      call recover_stresses(m, res%body_fields_t, status)
      if (.not. status%ok()) return
      res%restrained = an%restrained
      ! what the run uses, for the headers and the result file
      res%info = run_info_t(plan=plan, solver=an%sys%solver%name(), system=an%sys%describe(), &
                            returning=an%returning, &
                            modified=an%modified, neq=an%map%neq, nres=an%map%nres, &
                            npair=an%npair, &
                            condensed=an%sys%condensed, system_bytes=an%sys%memory_bytes(), &
                            max_repeats=an%maxrep, &
                            autoinc=m%autoinc, autoinc_min=m%autoinc_min, &
                            autoinc_easy=m%autoinc_easy, &
                            max_switch=MAX_SWITCH)
   end subroutine start_run

   !> The loop over the deck's increments; with AUTOINC each may be cut into
   !! steps (halved when a step fails, doubled after easy ones).
   subroutine solve_history(m, an, res, out, status)
      type(model_t), intent(in) :: m
      type(analysis_t), intent(inout) :: an
      type(run_result_t), intent(inout) :: res
      type(run_report_t), intent(inout) :: out
      type(status_t), intent(inout) :: status
      type(attempt_t) :: att
      type(step_record_t) :: srec
      real(dp), allocatable :: fext(:, :), fext_new(:, :), carry(:), dlam(:), ve_old(:), pa_old(:)
      integer :: inc, nstep, cuts, ic
      integer :: nlast, nref                        !! AUTOINC: solutions of the last step, and of
                                                    !! the last step before the step was cut
      logical :: first, rough_newton, last, written, full
      real(dp) :: frac, step, s
      real(dp) :: msize                             !! the model's largest extent (runaway checks)

      allocate (fext(2, m%npoin), fext_new(2, m%npoin), carry(an%map%neq), dlam(m%ncase), &
                ve_old(an%npair))
      msize = max(maxval(m%coord(1, :)) - minval(m%coord(1, :)), &
                  maxval(m%coord(2, :)) - minval(m%coord(2, :)))
      fext = 0.0_dp
      carry = 0.0_dp
      nstep = 0
      first = .true.
      rough_newton = an%returning .and. res%contact%has_rough   ! Newton return of the rough pairs
      step = 1.0_dp
      nlast = 0
      nref = 0
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
            if (first .and. an%has_contact .and. res%contact%has_rough .and. &
                  m%contact%opts%p_start <= 0.0_dp) then
               call start_pressure(m, an%fcase, dlam, res%contact, status)
               if (.not. status%ok()) exit deck
            end if
            call attempt_with_pretension(an, m, res%contact, dlam, carry, fext_new, first, att, &
                                         status)
            call check_finite_attempt(att%du, res%contact, an%has_contact, status)
            if (an%has_contact .and. att%converged) then
               call check_runaway(res%contact, msize, nstep + 1, status)
            end if
            if (.not. m%autoinc) then
               if (.not. status%ok()) exit deck
               if (an%has_contact) call attempt_failure(att, res%contact, m%contact%opts, &
                                                        rough_newton, m%autoinc, &
                                                        an%maxrep, nstep + 1, status)
               if (.not. status%ok()) exit deck
            else if (.not. status%ok() .or. .not. att%converged .or. res%contact%chatter) then
               ! cut the step and try again from the committed state
               if (s <= m%autoinc_min*(1.0_dp + 1.0e-9_dp)) then
                  if (status%ok() .and. an%has_contact) call &
                        attempt_failure(att, res%contact, m%contact%opts, &
                                                        rough_newton, m%autoinc, an%maxrep, &
                                                        nstep + 1, status)
                  if (status%ok()) call status%set(STAT_NO_CONVERGENCE, &
                                                   'contact states keep changing in increment '// &
                                                   itoa(nstep + 1)//' even at the smallest step')
                  status%message = status%message//' (automatic increments: smallest step '// &
                                   rtoa(m%autoinc_min)//' of deck increment '//itoa(inc)// &
                                   ' reached)'
                  exit deck
               end if
               status = status_t()
               step = max(0.5_dp*s, m%autoinc_min)
               cuts = cuts + 1
               call out%note_cut(inc, step)
               cycle
            end if

            ! ---- the step is accepted: the full displacement increment where the step's body
            ! fields are needed (written, listed or the last; contact models: the contact
            ! solution is exact whatever the recovery), then commit
            nstep = nstep + 1
            frac = frac + s
            last = inc == m%nincs .and. frac >= 1.0_dp - 1.0e-12_dp
            ! OPTIONS RESULTS n: only every n-th step and the last go into the result file
            written = last .or. mod(nstep, m%results_every) == 0
            full = written .or. .not. an%has_contact .or. out%lists_every_step()
            call an%sys%recover(att%du, full, status)
            if (.not. status%ok()) exit deck
            an%pending = .not. full
            first = .false.
            fext = fext_new
            carry = att%carry
            ve_old = res%contact%s%ve
            pa_old = res%contact%s%pa
            if (an%has_contact) call energy_begin(res%contact, res%energy)
            if (an%has_contact) call commit_increment(m%contact, res%contact)
            call an%pred%accept(att%du, dlam)
            res%disp = res%disp + att%du
            srec = step_record_t(step=nstep, deck_increment=inc, fraction=frac, cuts=cuts, &
                                 lambda=m%lambda(:, inc - 1) + &
                                 (m%lambda(:, inc) - m%lambda(:, inc - 1))*frac, &
                                 solutions=att%solutions, repeats=att%repeats, &
                                 residual=merge(att%rnorm, 0.0_dp, an%has_contact), &
                                 penetration=res%contact%violation, &
                                 augmentations=res%contact%augmentations, &
                                 status=merge(STEP_CONVERGED, STEP_UNSETTLED, att%converged), &
                                 contact=an%has_contact, &
                                 ideal=res%contact%has_ideal, last=last, written=written, full=full)
            if (an%has_contact) then
               call energy_commit(m%contact, res%contact, nstep, srec%lambda, res%energy)
            end if
            if (an%has_contact) srec%drift = law_drift(m%contact, res%contact)
            if (an%has_contact) then
               call tangential_drift(m%contact, res%contact, an%tlaw, srec%drift_t, &
                                     srec%drift_t_pair)
            end if
            if (an%has_contact) then
               call sliding_warning(res%contact, an%spacing, nstep, an%warned_closure, res%warnings)
            end if
            if (an%has_contact) call out%note_reversals(m%contact, pa_old, res%contact%s%pa, srec, &
                                                        res%warnings)
            call finish_step(m, an, res, out, fext, ve_old, msize, srec, status)
            if (.not. status%ok()) exit deck
            ! AUTOINC: after an easy step the next one doubles.  Easy: at most NEASY solutions,
            ! or, while the step is cut, no more than the reference -- the solutions of the last
            ! step accepted before the cut (of the first step after it, where the run's first
            ! step was cut): a contact increment's solutions have a floor that does not shrink
            ! with the step (mode changes, multiplier updates), so a cut step that costs what
            ! the steps before the trouble cost is as easy as they were (docs/robustness.md)
            if (cuts > 0 .and. nlast > 0) nref = nlast
            if (m%autoinc .and. .not. res%contact%chatter .and. (att%solutions <= m%autoinc_easy &
                .or. att%solutions <= nref)) step = min(1.0_dp, 2.0_dp*step)
            if (cuts > 0 .and. nlast == 0) nref = att%solutions
            if (step >= 1.0_dp) nref = 0
            nlast = att%solutions
            cuts = 0
         end do
      end do deck
      call res%trim_history()
      if (an%pending) call complete_postponed(m, an, res, fext)
   end subroutine solve_history

   !> A run that stopped after steps whose full field was postponed: the
   !! postponed part of the displacements (one more recovery of the contact
   !! system with a zero increment, on the reference springs, which keep it
   !! regular whatever the springs of the failed attempt were) and the body
   !! fields of the last finished step, for the summary and the caller.
   subroutine complete_postponed(m, an, res, fext)
      type(model_t), intent(in) :: m
      type(analysis_t), intent(inout) :: an
      type(run_result_t), intent(inout) :: res
      real(dp), intent(in) :: fext(:, :)            !! external forces of the last finished step
      type(status_t) :: st                          !! (the run's own failure is what it reports)
      real(dp), allocatable :: b(:), du(:, :), fsp(:, :)
      allocate (b(an%map%neq), du(2, m%npoin))
      b = 0.0_dp
      du = 0.0_dp
      call an%sys%set_springs(an%kref, st)
      call an%sys%begin_attempt()
      if (st%ok()) call an%sys%solve(b, du, st)
      du = 0.0_dp                                   ! (the zero increment at the contact dofs)
      if (st%ok()) call an%sys%recover(du, .true., st)
      if (.not. st%ok()) return
      an%pending = .false.
      res%disp = res%disp + merge(0.0_dp, du, an%restrained)
      call body_step_fields(m, an, res, fext, fsp, st)
   end subroutine complete_postponed

   !> The body fields of a step from its full displacements: stresses, spring
   !! forces at the nodes (fsp) and reactions.
   subroutine body_step_fields(m, an, res, fext, fsp, status)
      type(model_t), intent(in) :: m
      type(analysis_t), intent(in) :: an
      type(run_result_t), intent(inout) :: res
      real(dp), intent(in) :: fext(:, :)
      real(dp), allocatable, intent(out) :: fsp(:, :)
      type(status_t), intent(inout) :: status
      call spring_nodal_forces(m%contact, res%contact, m%npoin, fsp)
      call recover_stresses(m, res%body_fields_t, status)
      if (status%ok()) call update_reactions(an%coup, an%map, fext, fsp, res%body_fields_t)
   end subroutine body_step_fields

   !> Fields, checks, output and progress of an accepted step.
   subroutine finish_step(m, an, res, out, fext, ve_old, msize, srec, status)
      type(model_t), intent(in) :: m
      type(analysis_t), intent(inout) :: an
      type(run_result_t), intent(inout) :: res
      type(run_report_t), intent(inout) :: out
      real(dp), intent(in) :: fext(:, :), ve_old(:)
      real(dp), intent(in) :: msize                 !! the model's largest extent
      type(step_record_t), intent(inout) :: srec
      type(status_t), intent(inout) :: status
      real(dp), allocatable :: fsp(:, :), fpm(:)
      real(dp) :: imb
      integer :: k

      ! the body fields where the full displacements were recovered (srec%full)
      if (srec%full) then
         call body_step_fields(m, an, res, fext, fsp, status)
      else
         call spring_nodal_forces(m%contact, res%contact, m%npoin, fsp)
      end if
      if (an%pret%n > 0) then
         ! the sections' springs are internal forces too; the force across each from its elements
         call pretension_nodal_forces(m, an%pret, res%disp, fsp)
         if (srec%full) call section_forces(m, res%disp, srec%pretension_force, fpm, status)
         if (srec%full) srec%pretension_shortening = [(section_shortening(m%pretensions(k), &
                                                    an%pret%sections(k)%w, res%disp), k=1, &
                                                    an%pret%n)]
      end if
      call check_finite_step(res%body_fields_t, res%contact, an%has_contact, srec%drift, &
                             srec%full, status)
      if (an%has_contact) call check_runaway_displacement(res%disp, msize, srec%step, status)
      if (.not. status%ok()) return

      ! invariants (SPEC §7): bodies in equilibrium (where their fields were computed, to
      ! round-off), no tension, |F_T| <= mu F_n, v_e non-decreasing; frozen states, drift: doubtful
      an%force_scale = max(an%force_scale, maxval(abs(fext)), maxval(abs(fsp)))
      imb = IMBALANCE_NOT_COMPUTED
      if (srec%full) then
         an%force_scale = max(an%force_scale, maxval(abs(res%react)))
         imb = body_imbalance(an%body, an%nbody, fext + res%react - fsp, an%force_scale, &
                              m%ntype == NTYPE_AXISYMMETRIC)
      end if
      call audit_step(m%contact, res%contact, ve_old, imb, &
                      imbalance_limit(an%absrow, an%map%id, res%disp, &
                      an%force_scale), an%has_contact, srec, an%force_scale)
      call note_doubts(res%doubts, srec, stderr)
      call res%append_history(srec)
      if (an%has_contact) call build_contact_fields(m%contact, res%contact, res%fields)
      if (an%has_contact) call energy_fields(m%contact, res%contact, res%energy, res%fields)
      if (srec%full .and. status%ok()) call estimate_error(m, res%body_fields_t, res%fields, status)

      call out%write_step(m, srec, res%body_fields_t, res%fields, status)
      if (.not. status%ok()) return
      res%completed = srec%step
   end subroutine finish_step

   !> The end of the run: the load cycles found, then the outputs' closing
   !! lines, summary and status (run_report's finish).
   subroutine close_outputs(m, res, out, status, set_up_failed)
      type(model_t), intent(in) :: m
      type(run_result_t), intent(inout) :: res
      type(run_report_t), intent(inout) :: out
      type(status_t), intent(inout) :: status   !! a failure to write an output ends it
      logical, intent(in) :: set_up_failed      !! the run stopped before its first increment
      type(run_end_t) :: fin
      if (.not. set_up_failed) then
         call energy_cycles(res%energy, res%cycles)
         fin%solutions = res%iterations
         fin%drift = res%drift
         fin%ua = res%contact%s%ua
         fin%pa = res%contact%s%pa
      end if
      fin%completed = res%completed
      fin%doubts = res%doubts
      if (res%doubts%steps > 0) fin%doubt_line = doubt_summary(res%doubts, res%completed)
      fin%cycles = res%cycles
      fin%info = res%info
      fin%warnings = res%warnings
      call out%finish(m, res%body_fields_t, res%fields, fin, status, res%reported)
   end subroutine close_outputs
end module incremental
