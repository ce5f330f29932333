!> The records of a run: what one accepted step, its fields and the run as a
!! whole leave behind, in the form both outputs (the HDF5 result file and the
!! listing) and the caller read.
!!
!! The layers that own a quantity fill its record once per step: the driver
!! the step record (convergence figures), the assembly layer the body fields
!! (stresses next to the element loops, reactions), the contact layer the
!! contact fields (p = F/A, state codes).  `io/results_hdf5` (the only module
!! that knows the HDF5 names) and `io/listing` take the records as they are;
!! neither knows the contact algorithm or a solver.  The records live in the
!! model layer because `io` may use only `io`, `model` and `core`.
!!
!! Life cycle of one run:
!!
!!     run_info_t        once, after the set-up (what the run uses: the run
!!                       plan, contact system, caps, automatic increments)
!!     body_fields_t     Gauss-point layout once, then every accepted step
!!     contact_fields_t  every accepted step (contact models)
!!     step_record_t     every accepted step
!!     run_doubts_t      every accepted step that is doubtful (frozen contact
!!                       states, law drift beyond DRIFT_LIMIT, invariant
!!                       violations): a run with one ends "doubtful", not
!!                       "completed"
module records
   use kinds, only: dp, i8
   use run_plan, only: run_plan_t
   implicit none
   private

   public :: step_record_t, body_fields_t, contact_fields_t, run_info_t, run_doubts_t
   public :: cycle_table_t, numbering_report_t
   public :: DRIFT_LIMIT, MAX_DOUBT_LINES
   public :: NS_OPEN, NS_LOADING, NS_UNLOADING, TS_STICK, TS_PLASTIC, TS_SLIP
   public :: STEP_CONVERGED, STEP_UNSETTLED

   !> Normal state codes of a pair (results `normal_state`).
   integer, parameter :: NS_OPEN = 0         !! open: no force
   integer, parameter :: NS_LOADING = 1      !! closed on the virgin curve (the ideal law: closed)
   integer, parameter :: NS_UNLOADING = 2    !! closed on the unloading/reloading branch
   !> Tangential state codes of a pair (results `tangential_state`).
   integer, parameter :: TS_STICK = 0        !! elastic (stick)
   integer, parameter :: TS_PLASTIC = 1      !! on the hardening branch
   integer, parameter :: TS_SLIP = 2         !! slip

   !> How an accepted step ended.
   integer, parameter :: STEP_CONVERGED = 0  !! met its convergence criterion
   integer, parameter :: STEP_UNSETTLED = 1  !! an EXPLICIT increment accepted with its slip forces
                                             !! unsettled (its out-of-balance force is carried on)

   !> Law drift (|F_n - A p(u_n)| / max F_n at the end of a step) beyond which a
   !! step is doubtful: 5 %, the accuracy the paper's explicit scheme is used
   !! for (docs/accuracy-and-stability.md); a converged Newton step has none.
   real(dp), parameter :: DRIFT_LIMIT = 0.05_dp
   !> Lines of detail a run keeps about its doubtful steps (the first ones).
   integer, parameter :: MAX_DOUBT_LINES = 20

   !> Figures of one accepted step (one group of the result file).
   type :: step_record_t
      integer :: step = 0                    !! number of the accepted step (the result group)
      integer :: deck_increment = 0          !! the deck increment it belongs to
      real(dp) :: fraction = 0.0_dp          !! how much of that deck increment is done after it
      integer :: cuts = 0                    !! halvings before it was accepted
                                             !! (automatic increments)
      real(dp), allocatable :: lambda(:)     !! (ncase) total load factor of every case
      integer :: solutions = 0               !! linear solutions (repeats included)
      integer :: repeats = 0                 !! solutions caused by mode changes
      real(dp) :: residual = 0.0_dp          !! relative out-of-balance force left (contact)
      real(dp) :: drift = 0.0_dp             !! largest departure of F_n from
                                             !! its curve, relative (contact)
      real(dp) :: drift_t = 0.0_dp           !! largest departure of F_T from
                                             !! the tangential law along the
                                             !! committed history, relative to the largest mu F_n
                                             !! (contact)
      integer :: drift_t_pair = 0            !! the pair of that largest departure (0: none)
      real(dp) :: imbalance = 0.0_dp         !! largest force imbalance of a body, relative
      real(dp) :: imbalance_limit = 1.0e-8_dp !! the imbalance beyond which it is doubtful
                                              !! (round-off included)
      integer :: violations = 0              !! invariant violations (SPEC §7)
      integer :: frozen = 0                  !! pairs whose modes were frozen (chatter)
      real(dp) :: penetration = 0.0_dp       !! ideal contact: largest |u_n| (closed) or stick slip
      integer :: augmentations = 0           !! ideal contact: multiplier updates
      logical :: converged = .true.          !! met its convergence criterion
                                             !! (not unsettled, no frozen pair)
      integer :: status = STEP_CONVERGED     !! STEP_CONVERGED or STEP_UNSETTLED
      logical :: contact = .false.           !! the model has contact: residual and drift apply
      logical :: ideal = .false.             !! some interface is ideal: penetration,
                                             !! augmentations apply
      logical :: last = .false.              !! the last step of the load history
      logical :: written = .false.           !! goes into the result file (OPTIONS RESULTS)
      logical :: full = .true.               !! its body fields were computed:
                                             !! full displacements, stresses,
                                             !! reactions, imbalance (written, listed or last steps
                                             !! of a contact run)
      character(len=:), allocatable :: doubts  !! why the step is doubtful ('' if it is not): frozen
                                               !! states, drift, violations, naming the pairs
      character(len=:), allocatable :: warnings  !! what the step did beyond
                                                 !! the laws' range, though not
                                                 !! doubtful (unloading beyond p*), naming the pairs
                                                 !! ('' if nothing)
      ! pretension sections (unallocated or empty without): the force across each (tension positive,
      ! from the internal forces of the elements on the +axis side of the cut) and its shortening
      real(dp), allocatable :: pretension_force(:)       !! (nsection) [force]
      real(dp), allocatable :: pretension_shortening(:)  !! (nsection) -delta [length]
   end type step_record_t

   !> Nodal and Gauss-point fields of the bodies after a step.
   type :: body_fields_t
      real(dp), allocatable :: disp(:, :)        !! (2, npoin) total displacements
      real(dp), allocatable :: react(:, :)       !! (2, npoin) reactions, zero at free dofs
      real(dp), allocatable :: sig_nd(:, :)      !! (4, npoin) stresses averaged at the nodes
      real(dp), allocatable :: sig_gp(:, :)      !! (4, ngp) Gauss-point stresses
      real(dp), allocatable :: xygp(:, :)        !! (2, ngp) Gauss-point coordinates
      integer, allocatable :: gp_start(:)        !! (nelem+1) first Gauss point of each element
      logical, allocatable :: restrained(:, :)   !! (2, npoin) restrained dofs (reactions listed)
      !> A posteriori error estimate (Zienkiewicz-Zhu, module error_estimate) of the step's
      !> stresses:
      !! eta_e = ||sigma* - sigma_h||_E,e / sqrt(||u_h||_E^2 + ||e*||_E^2) per element (norms of the
      !! whole
      !! model in the denominator), so that sqrt(sum eta_e^2) = estimated_error.
      real(dp), allocatable :: error_indicator(:)  !! (nelem) eta_e, fraction [-]
      real(dp) :: estimated_error = 0.0_dp       !! eta = ||e*||_E / sqrt(||u_h||_E^2
                                                 !! + ||e*||_E^2), fraction [-]
      real(dp) :: error_norm = 0.0_dp            !! ||e*||_E = ||sigma* - sigma_h||_E,
                                                 !! sqrt of energy
      real(dp) :: energy_norm = 0.0_dp           !! ||u_h||_E, sqrt of energy
      logical :: estimated = .false.             !! the estimate belongs to the current stresses
   end type body_fields_t

   !> Per-pair contact quantities after a step (results group `contact`).
   type :: contact_fields_t
      real(dp), allocatable :: pressure(:)              !! F_n / A_j, extrapolated at zero area
      real(dp), allocatable :: shear(:)                 !! F_T / A_j, extrapolated at zero area
      real(dp), allocatable :: force_normal(:)          !! F_n
      real(dp), allocatable :: force_tangential(:)      !! F_T
      real(dp), allocatable :: closure(:)               !! u_n
      real(dp), allocatable :: slip(:)                  !! u_T
      real(dp), allocatable :: slip_irreversible(:)     !! u_T^p
      real(dp), allocatable :: slip_gross(:)            !! its gross-slip part
      real(dp), allocatable :: effective_slip(:)        !! v_e
      real(dp), allocatable :: friction(:)              !! friction coefficient used
      integer, allocatable :: normal_state(:)           !! NS_*
      integer, allocatable :: tangential_state(:)       !! TS_*
      real(dp), allocatable :: stiffness_normal(:)      !! K_n used
      real(dp), allocatable :: stiffness_tangential(:)  !! K_T used
      integer, allocatable :: switches(:)               !! mode changes of the pair in the step
      !> How well the interface resolves the contact pressure (module error_estimate): per pair the
      !! largest jump of the pressure to its neighbouring pairs on the interface, relative to the
      !! interface's peak pressure; per interface the contact zone's width and its closed pairs.
      real(dp), allocatable :: resolution(:)            !! (npair) pressure jump / peak pressure [-]
      real(dp), allocatable :: zone_width(:)            !! (niface) width of the contact
                                                        !! zone in the model [length]
      integer, allocatable :: zone_pairs(:)             !! (niface) closed pairs in it
      real(dp), allocatable :: zone_jump(:)             !! (niface) largest resolution(:)
                                                        !! of its pairs [-]
      !> Energy dissipated by the contact laws (module contact_energy), cumulative from the start of
      !> the
      !! run, in the model's force x length: per pair the frictional work of the irreversible
      !! tangential
      !! displacement and the normal law's hysteresis; per interface their sum, its part in this
      !! step, the
      !! interface's total tangential force and the area-weighted mean u_T of its closed pairs.
      real(dp), allocatable :: dissipation_tangential(:)  !! (npair)
      real(dp), allocatable :: dissipation_normal(:)      !! (npair)
      real(dp), allocatable :: dissipated_energy(:)       !! (niface) cumulative,
                                                          !! normal + tangential
      real(dp), allocatable :: dissipated_increment(:)    !! (niface) in this step
      real(dp), allocatable :: tangential_force_total(:)  !! (niface) sum of F_T
      real(dp), allocatable :: slip_mean(:)               !! (niface) area-weighted mean
                                                          !! u_T of the closed pairs
   end type contact_fields_t

   !> The load cycles of a periodic history (module contact_energy): per cycle its first and last
   !! step, and per cycle and interface the energy dissipated, the half ranges of the interface's
   !! total
   !! tangential force and mean slip, their ratio (secant stiffness), the loss factor
   !! energy / (2 pi U), U = force_amplitude slip_amplitude / 2, and the damping ratio (half of it).
   type :: cycle_table_t
      integer :: ncycle = 0
      integer, allocatable :: first(:), last(:)          !! (ncycle) steps (result
                                                         !! groups) of its ends
      real(dp), allocatable :: energy(:, :)              !! (niface, ncycle) [force x length]
      real(dp), allocatable :: force_amplitude(:, :)     !! (niface, ncycle) [force]
      real(dp), allocatable :: slip_amplitude(:, :)      !! (niface, ncycle) [length]
      real(dp), allocatable :: secant_stiffness(:, :)    !! (niface, ncycle) [force/length];
                                                         !! 0 without slip
      real(dp), allocatable :: loss_factor(:, :)         !! (niface, ncycle) [-]; 0 where U = 0
      real(dp), allocatable :: damping_ratio(:, :)       !! (niface, ncycle) [-]
      logical, allocatable :: ratios_defined(:, :)       !! (niface, ncycle) the three ratios
                                                         !! above mean something: a rough
                                                         !! interface whose energy fits in its
                                                         !! (sum F_T, mean u_T) loop's rectangle
                                                         !! 4 F_amp u_amp (0 where not)
   end type cycle_table_t

   !> What a run uses, for the header of the listing and the terminal and the
   !! root attributes of the result file (the model is not written back).
   type :: run_info_t
      type(run_plan_t) :: plan                      !! how the run solves: solver
                                                    !! and why, contact system,
                                                    !! order of the equations, scheme (module
                                                    !! run_plan)
      character(len=:), allocatable :: solver       !! name of the linear solver of the bodies
      character(len=:), allocatable :: system       !! the contact system's line
                                                    !! ('' for the full system)
      logical :: returning = .false.                !! contact scheme: RETURN update (Newton) ...
      logical :: modified = .false.                 !! ... with the stiffness kept (modified Newton)
      integer :: neq = 0                            !! equations
      integer :: nres = 0                           !! restrained dofs
      integer :: npair = 0                          !! contact pairs
      logical :: condensed = .false.                !! bodies condensed onto the contact equations
      integer(i8) :: system_bytes = 0               !! memory of the contact
                                                    !! system beyond the solver
      integer :: max_repeats = 0                    !! cap on solutions of one increment, as used
      logical :: autoinc = .false.                  !! automatic increments
      real(dp) :: autoinc_min = 0.0_dp              !! their smallest step, fraction
                                                    !! of a deck increment
      integer :: autoinc_easy = 0                   !! solutions of an easy step
      integer :: max_switch = 0                     !! mode changes after which a
                                                    !! rough pair's modes are frozen
   end type run_info_t

   !> The doubtful steps of a run: how many of each kind, and the first
   !! MAX_DOUBT_LINES of them in words ("increment 3: ..."), for the
   !! terminal, the listing and the result file's status.
   type :: run_doubts_t
      integer :: steps = 0                          !! doubtful steps
      integer :: frozen = 0                         !! steps with frozen contact states
      integer :: drift = 0                          !! steps with law drift beyond DRIFT_LIMIT
      integer :: violations = 0                     !! steps with invariant violations
      integer :: first = 0                          !! the first doubtful step
      character(len=:), allocatable :: details      !! one line per doubtful step
                                                    !! (new-line separated)
   end type run_doubts_t

   !> What the equation numbering did (driver's equation_numbering), for the
   !! header of the listing and the terminal and the result file's /summary.
   type :: numbering_report_t
      character(len=:), allocatable :: method      !! 'RCM' or 'NONE'
      character(len=:), allocatable :: reason      !! why this method
      integer(i8) :: profile_before = 0            !! skyline length in the user's order
      real(dp) :: mean_before = 0.0_dp
      integer :: max_before = 0
      integer(i8) :: profile_after = 0             !! skyline length in the order used
      real(dp) :: mean_after = 0.0_dp
      integer :: max_after = 0
      character(len=:), allocatable :: solver_choice   !! the automatic choice of the
                                                       !! solver and why ('' none)
   end type numbering_report_t

end module records
