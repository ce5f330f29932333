!> The records of the contact algorithm: the committed state of a pair (end of
!! an increment), its mode within an increment (the assumption the solve
!! uses), and the state of all pairs together (contact_state_t), with the
!! lists of the rough and the ideal pairs that the per-law loops run over.
!! No procedures: the rooms that work on these records are contact_state
!! (init, begin and commit of an increment, the audits), contact_rough_pair
!! (one rough pair), contact_ideal_pair (the ideal pairs) and the facade
!! contact_algorithm (the evaluation loop); docs/architecture.md.
module contact_pair_types
   use kinds, only: dp
   ! the state codes are those of the contact fields record (model layer)
   use records, only: NS_OPEN, NS_LOADING, NS_UNLOADING, TS_STICK, TS_PLASTIC, TS_SLIP
   implicit none
   private

   public :: pair_state_t, pair_mode_t, contact_state_t
   public :: NS_OPEN, NS_LOADING, NS_UNLOADING, TS_STICK, TS_PLASTIC, TS_SLIP
   public :: MAX_SWITCH

   !> Mode changes of one rough pair within one increment; a pair that reaches
   !! it keeps its last mode for the rest of the increment (frozen: chatter).
   integer, parameter :: MAX_SWITCH = 6

   !> Committed state of one pair (end of an increment).
   type :: pair_state_t
      logical :: closed = .false.
      logical :: on_unloading = .false.   !! on the unloading/reloading branch through A
      real(dp) :: ua = 0.0_dp, pa = 0.0_dp  !! reversal point A (closure, pressure)
      real(dp) :: un = 0.0_dp             !! total closure (u_b - u_a).n - g0
      real(dp) :: ut = 0.0_dp             !! total tangential displacement (u_a - u_b).t
      real(dp) :: fn = 0.0_dp, ft = 0.0_dp  !! spring forces
      real(dp) :: utp = 0.0_dp            !! irreversible tangential displacement (SPEC §2.3 a)
      real(dp) :: utp_gross = 0.0_dp      !! gross-slip part only (SPEC §2.3 b)
      real(dp) :: ve = 0.0_dp             !! effective slip, path length of the chosen definition
      real(dp) :: xb = 0.0_dp             !! back force: centre of the elastic
                                          !! band |F_T - xb| <= 0.625 mu F_n
      real(dp) :: fy = 0.0_dp             !! EXPLICIT: largest |F_T| reached
                                          !! on the hardening branch or in slip
      integer :: tstate = TS_STICK
      real(dp) :: mu = 0.0_dp             !! friction coefficient used in the increment
      real(dp) :: kn = 0.0_dp, kt = 0.0_dp  !! spring stiffnesses of the increment
   end type pair_state_t

   !> The assumption for one pair within an increment.
   type :: pair_mode_t
      logical :: closed = .false.
      logical :: newly_closed = .false.
      logical :: held = .false.           !! RETURN: held at the zero-force point instead of opening
      logical :: touching = .false.       !! RETURN: at the zero-force point
                                          !! of its branch to round-off
                                          !! (touching_band) in the last evaluation
      logical :: on_unloading = .false.
      real(dp) :: ua = 0.0_dp, pa = 0.0_dp
      integer :: tstate = TS_STICK
      integer :: tsign = 0                !! direction (+-1) of the branch
                                          !! or slip of tstate (0: stick)
      real(dp) :: xb = 0.0_dp             !! back force of the tangential law after the increment
      real(dp) :: kn = 0.0_dp             !! normal spring stiffness for the solve
      real(dp) :: kte = 0.0_dp            !! elastic tangential spring stiffness of the increment
      real(dp) :: kt = 0.0_dp             !! tangential spring stiffness for the solve
      real(dp) :: uthr = 0.0_dp           !! closure at which the pair (re)closes
      real(dp) :: mu = 0.0_dp
      integer :: nswitch = 0              !! mode changes in the increment so far (see MAX_SWITCH)
      logical :: settled = .false.        !! frozen (MAX_SWITCH), but free to change its mode
                                          !! it keeps it at the converged solution
                                          !! (contact_algorithm's settle_frozen)
      integer :: tvisited = 0             !! RETURN: the tangential states
                                          !! (tstate, tsign) met in the
                                          !! increment, one bit each (tstate_bit)
      logical :: tstable = .false.        !! RETURN: back in a state met before:
                                          !! the secant stiffness of
                                          !! the law over the increment from then on
                                          !! (tangential_return)
      real(dp) :: sdir = 0.0_dp           !! ideal law: direction (+-1) of the current slip
      logical :: released = .false.       !! ideal law: kept closed in tension until the multipliers
                                          !! settled, then let open (no tension band any more)
      logical :: hold = .false.           !! ideal law: the multipliers were just updated; the
                                          !! next evaluation keeps the modes (see
                                          !! augment_multipliers)
      integer :: tswitch = 0              !! ideal law: changes of the tangential
                                          !! mode in the increment
      logical :: tfixed = .false.         !! ideal law: the tangential mode
                                          !! cycled (IDEAL_TSWITCH changes);
                                          !! the secant stiffness ksec in the matrix from then on
                                          !! (evaluate_ideal)
      real(dp) :: ksec = 0.0_dp           !! ideal law, tfixed: secant of the projection over du_T
      logical :: anchored = .false.       !! RETURN, the second pass at zero
                                          !! load: the regularising springs
                                          !! are elastic from (un_anc, ut_anc)
                                          !! (anchor_regularisation)
      real(dp) :: un_anc = 0.0_dp, ut_anc = 0.0_dp  !! closure and slip increment at the anchor
      real(dp) :: fn_anc = 0.0_dp, ft_anc = 0.0_dp  !! the anchored springs' forces
                                                    !! in the last evaluation
      logical :: rest = .false.           !! RETURN, an increment to zero load: the pair's
                                          !! law replaced by the rest spring K (u - u_thr)
                                          !! while the bodies are placed at rest
                                          !! (contact_algorithm's start_rest)
   end type pair_mode_t

   type :: contact_state_t
      type(pair_state_t), allocatable :: s(:)     !! committed
      type(pair_mode_t), allocatable :: md(:)     !! current modes
      real(dp), allocatable :: fn(:), ft(:)       !! current forces
      real(dp), allocatable :: dun(:), dut(:)     !! current increments of closure and slip
      real(dp) :: p_start = 0.0_dp                !! p_m of eq. (4.1)
      real(dp) :: p_incr = 0.0_dp                 !! RETURN: pressure the increment
                                                  !! is expected to bring
                                                  !! (contact_start's increment_pressure; 0: none)
      logical :: chatter = .false.                !! a pair exhausted its mode changes
      logical :: regularise = .true.              !! RETURN: a pair slipping at
                                                  !! vanishing normal force keeps
                                                  !! K_T^e (vanishing_slip_kt) until
                                                  !! drop_regularisation
      logical :: regularise_slip = .false.        !! RETURN: every closed pair in slip
                                                  !! keeps K_T^e (regularise_slip:
                                                  !! the system was singular without)
      ! ideal contact (augmented Lagrangian)
      logical :: has_ideal = .false.              !! some interface is IDEAL
      logical :: has_rough = .false.              !! some interface is ROUGH
      real(dp), allocatable :: lam_n(:), lam_t(:) !! multipliers of the current Uzawa iterate
      real(dp), allocatable :: eps_n(:), eps_t(:) !! penalty stiffnesses [force/length]
      real(dp) :: tol_pen = 0.0_dp                !! accepted penetration and stick slip [length]
      real(dp) :: violation = 0.0_dp              !! largest penetration / stick
                                                  !! slip at the last check
      integer :: augmentations = 0                !! multiplier updates in the current increment
      real(dp) :: fref = 0.0_dp                   !! largest normal force of an
                                                  !! ideal pair committed so far
      ! the pairs by law, ascending (contact_init): the loops of the algorithm run over
      ! these lists, so that no loop asks a pair for its law
      integer, allocatable :: rough(:)            !! the rough pairs
      integer, allocatable :: ideal(:)            !! the ideal pairs
      integer, allocatable :: kloc(:)             !! position of each pair among those of its
                                                  !! interface (its per-pair R, ifc%r_t(kloc))
      logical :: coulomb = .false.                !! the slip bound is mu F_n (else
                                                  !! mu lam_n) in this increment
   end type contact_state_t
end module contact_pair_types
