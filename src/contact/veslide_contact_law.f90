!> The contact law: what the interface between the rigid surface and the solid does, cell by
!> cell, written once for the solvers, their passes, the residual, the analyses and the driver.
!>
!> A law is
!>  - its kind (a LAW_* id, named by `law_names`) and its parameters (`param`, in the law's own
!>    order and SI units);
!>  - its per-cell maps (`veslide_contact_law_maps.inc`, included here and in the pass modules
!>    so that they are inlined; their CUDA twins in `veslide_contact_law.cuh`):
!>      project(v)     the proximal map the splitting solvers apply to a pressure-like value;
!>      in_contact(p)  what counts as contact (in_contact_shifted(v, c): that of project(v - c));
!>      below(p)       a pressure past the law's bound, which an active-set solver clips;
!>      penetrates(g)  a gap past the law's bound, which an active-set solver admits to its set;
!>  - its contribution to the residual (`measures`: penetration, complementarity, negative
!>    pressure, from the sums over the grid the residual passes take; veslide_contact adds the
!>    load error and forms the residual), and what the analyses ask of a field (`contact`: the
!>    contact cells; `project`: the field made admissible, a solver's start).
!> The laws:
!>  - the hard wall (`LAW_HARD_WALL`, Signorini's conditions) p >= 0, g >= 0, p g = 0, contact
!>    where p > 0, without parameters;
!>  - two adhesive laws (`LAW_EXPONENTIAL`, `LAW_DUGDALE`, input group &adhesion): the traction
!>    is p = p_rep - sigma(g), the repulsive pressure p_rep of the hard wall (p_rep >= 0, g >= 0,
!>    p_rep g = 0) less an attraction sigma(g) >= 0 that depends on the gap alone; contact is
!>    where the gap is closed (g = 0, which p alone cannot tell: p > -sigma(0) also out of
!>    contact). Parameters [w, rho, sigma0] (`ADH_ENERGY`, `ADH_RANGE`, `ADH_STRESS`): the work of
!>    adhesion w [J/m^2] = the integral of sigma over the gap, the range rho [m] and the largest
!>    attraction sigma0 = w/rho [Pa]. Exponential: sigma(g) = sigma0 exp(-g/rho) (the
!>    contact-mechanics challenge's short-range law); Dugdale (Maugis' cohesive zone):
!>    sigma(g) = sigma0 for g < rho, 0 beyond. Their interaction energy per area is
!>    V(g) = -integral_g^inf sigma, so sigma = V' and p_rep = p + V'(g) is the gradient of the
!>    total energy with respect to the gap (veslide_solver_gcg). A pass takes the law whole and chooses its
!> maps once per call: a `select case` on `kind` outside its loop over cells (the CPU twins), a
!> template argument chosen by `vs::with_law` (the CUDA twins); never a choice per cell. Which
!> solver takes which law: `veslide_solver_table`.
!>
!> A new law (an adhesive one: a traction that is the repulsive pressure less an attraction
!> depending on the gap, for the splitting solvers) is its id and name here, its maps in the
!> include file and in the CUDA header, its `case` in the field procedures below and in each pass
!> that applies a law (veslide_contact_passes, veslide_dr_passes, veslide_anderson_passes), its
!> column in the solver table, and its input group (docs/development.md).
module veslide_contact_law
    use veslide_kinds, only: dp, pi
    use veslide_strings, only: name_index
    implicit none
    private
    public :: contact_law_t, law_id, law_names, law_count, law_max_params, LAW_HARD_WALL, LAW_EXPONENTIAL, &
              LAW_DUGDALE, ADH_ENERGY, ADH_RANGE, ADH_STRESS, new_adhesive_law
    public :: exponential_attraction, exponential_energy, dugdale_attraction, dugdale_energy
    public :: hard_wall_project, hard_wall_in_contact, hard_wall_in_contact_shifted, hard_wall_below, &
              hard_wall_penetrates

    integer, parameter :: LAW_HARD_WALL = 1, LAW_EXPONENTIAL = 2, LAW_DUGDALE = 3
    !> The laws there are (LAW_* ids 1..law_count)
    integer, parameter :: law_count = 3
    !> Names of the laws, indexed by their LAW_* id (the adhesive ones: &adhesion law)
    character(len=*), parameter :: law_names(law_count) = [character(len=11) :: 'hard_wall', 'exponential', &
                                                           'dugdale']
    !> Where an adhesive law keeps its parameters in contact_law_t%param
    integer, parameter :: ADH_ENERGY = 1, ADH_RANGE = 2, ADH_STRESS = 3
    !> The most parameters a law has
    integer, parameter :: law_max_params = 4

    !> One contact law: its kind and parameters (the default: the hard wall)
    type :: contact_law_t
        integer :: kind = LAW_HARD_WALL                       !! LAW_* id
        real(dp) :: param(law_max_params) = 0.0_dp            !! the law's parameters (none for the hard wall)
    contains
        procedure :: name => law_name
        procedure :: contact => law_contact
        procedure :: project => law_project
        procedure :: measures => law_measures
        procedure :: adhesive => law_adhesive
        procedure :: attraction => law_attraction
        procedure :: repulsive => law_repulsive
        procedure :: energy => law_energy
        procedure :: closed => law_closed
        procedure :: zone => law_zone
    end type contact_law_t

contains

    !> LAW_* id from a law's name; 0 when unknown
    pure integer function law_id(name) result(id)
        character(len=*), intent(in) :: name
        id = name_index(name, law_names)
    end function law_id

    !> The adhesive law of id `kind` (LAW_EXPONENTIAL or LAW_DUGDALE) with work of adhesion
    !> `energy` [J/m^2] and range `range` [m] (its largest attraction: energy/range)
    pure function new_adhesive_law(kind, energy, range) result(law)
        integer, intent(in) :: kind
        real(dp), intent(in) :: energy, range
        type(contact_law_t) :: law
        law%kind = kind
        law%param(ADH_ENERGY) = energy
        law%param(ADH_RANGE) = range
        law%param(ADH_STRESS) = energy/range
    end function new_adhesive_law

    !> Does the law attract (an adhesive law)?
    elemental logical function law_adhesive(self) result(yes)
        class(contact_law_t), intent(in) :: self
        yes = self%kind == LAW_EXPONENTIAL .or. self%kind == LAW_DUGDALE
    end function law_adhesive

    !> The attraction sigma(g) [Pa] at gaps `g` [m] (zero for the hard wall)
    pure function law_attraction(self, g) result(s)
        class(contact_law_t), intent(in) :: self
        real(dp), intent(in) :: g(:, :)
        real(dp) :: s(size(g, 1), size(g, 2))
        associate (s0 => self%param(ADH_STRESS), r => self%param(ADH_RANGE))
            select case (self%kind)
            case (LAW_EXPONENTIAL)
                s = exponential_attraction(g, s0, r)
            case (LAW_DUGDALE)
                s = dugdale_attraction(g, s0, r)
            case default
                s = 0.0_dp
            end select
        end associate
    end function law_attraction

    !> The repulsive pressure p_rep = p + sigma(g) [Pa] of tractions `p` at gaps `g` [m], with the
    !> attraction in the law's graph nearest to balancing p where the graph allows a choice: at
    !> the Dugdale zone's edge g = rho any attraction in [0, sigma0] (the jump's vertical segment,
    !> where the solver holds a cell the zone's edge stops)
    pure function law_repulsive(self, p, g) result(prep)
        class(contact_law_t), intent(in) :: self
        real(dp), intent(in) :: p(:, :), g(:, :)
        real(dp) :: prep(size(g, 1), size(g, 2))
        prep = p + self%attraction(g)
        if (self%kind == LAW_DUGDALE) then
            where (g == self%param(ADH_RANGE)) prep = p + min(max(-p, 0.0_dp), self%param(ADH_STRESS))
        end if
    end function law_repulsive

    !> The interaction energy V(g) [J/m^2] at gaps `g` [m] (V(infinity) = 0, V(0) = -w; zero for
    !> the hard wall)
    pure function law_energy(self, g) result(v)
        class(contact_law_t), intent(in) :: self
        real(dp), intent(in) :: g(:, :)
        real(dp) :: v(size(g, 1), size(g, 2))
        associate (s0 => self%param(ADH_STRESS), r => self%param(ADH_RANGE))
            select case (self%kind)
            case (LAW_EXPONENTIAL)
                v = exponential_energy(g, s0, r)
            case (LAW_DUGDALE)
                v = dugdale_energy(g, s0, r)
            case default
                v = 0.0_dp
            end select
        end associate
    end function law_energy

    !> The law's cohesive zone [m] on a solid of contact modulus `modulus` [Pa]: l = pi E* w/(4
    !> sigma0^2), the length over which the attraction acts beside a contact edge at rest (Maugis's
    !> and Dugdale's zone in the JKR limit, with sigma0 = w/rho for the exponential law)
    elemental real(dp) function law_zone(self, modulus) result(l)
        class(contact_law_t), intent(in) :: self
        real(dp), intent(in) :: modulus
        l = pi*modulus*self%param(ADH_ENERGY)/(4.0_dp*self%param(ADH_STRESS)**2)
    end function law_zone

    !> The closed cells of an adhesive law's solution: gap exactly zero (the solvers close a cell
    !> by setting its gap to 0; a fresh gap from K p is zero there to round-off only, so the
    !> solver's gap, not a recomputed one, decides)
    pure function law_closed(self, g) result(yes)
        class(contact_law_t), intent(in) :: self
        real(dp), intent(in) :: g(:, :)
        logical :: yes(size(g, 1), size(g, 2))
        yes = g <= 0.0_dp
        if (.not. self%adhesive()) yes = .false.
    end function law_closed

    !> The law's name
    pure function law_name(self) result(name)
        class(contact_law_t), intent(in) :: self
        character(len=:), allocatable :: name
        name = 'unknown'
        if (self%kind >= 1 .and. self%kind <= law_count) name = trim(law_names(self%kind))
    end function law_name

    !> The contact cells of the pressure field `p` and the gap `g`: where the law says a cell is in
    !> contact (the hard wall: p > 0; an adhesive law: g = 0, from the solver's gap, which it
    !> needs)
    pure function law_contact(self, p, g) result(yes)
        class(contact_law_t), intent(in) :: self
        real(dp), intent(in) :: p(:, :)
        real(dp), intent(in), optional :: g(:, :)
        logical :: yes(size(p, 1), size(p, 2))
        select case (self%kind)
        case (LAW_HARD_WALL)
            yes = hard_wall_in_contact(p)
        case (LAW_EXPONENTIAL, LAW_DUGDALE)
            yes = .false.
            if (present(g)) yes = self%closed(g)
        case default
            yes = .false.
        end select
    end function law_contact

    !> The field `v` made admissible for the law: its proximal map cell by cell (the hard wall:
    !> clipped at zero)
    pure function law_project(self, v) result(p)
        class(contact_law_t), intent(in) :: self
        real(dp), intent(in) :: v(:, :)
        real(dp) :: p(size(v, 1), size(v, 2))
        select case (self%kind)
        case (LAW_HARD_WALL)
            p = hard_wall_project(v)
        case default
            p = v
        end select
    end function law_project

    !> The law's measures of a candidate (p, g), from sums over the grid: the smallest gap `gmin`,
    !> sum(p g) `spg`, sum(|p|) `sp`, the smallest pressure `pmin`; the height scale `hs` and the
    !> pressure scale `p_mean`. Returns [penetration, complementarity, negative pressure]; for the
    !> hard wall max(-g)/h_s, |sum p g|/(sum p * h_s) and max(-p)/p_mean (veslide_contact); an
    !> adhesive law the same of its repulsive pressure p_rep = p + sigma(g) but for the
    !> complementarity, which its caller passes as `spg` already measured cell by cell:
    !> max min(|p_rep|/p_s, g/h_s) (a sum would weigh the open cells' |p_rep| <= tolerance by
    !> their gaps, large far from contact)
    pure function law_measures(self, gmin, spg, sp, pmin, hs, p_mean) result(m)
        class(contact_law_t), intent(in) :: self
        real(dp), intent(in) :: gmin, spg, sp, pmin, hs, p_mean
        real(dp) :: m(3)
        select case (self%kind)
        case (LAW_HARD_WALL)
            m(1) = max(0.0_dp, -gmin)/hs
            m(2) = abs(spg)/(sp*hs)
            m(3) = max(0.0_dp, -pmin)/p_mean
        case (LAW_EXPONENTIAL, LAW_DUGDALE)
            m(1) = max(0.0_dp, -gmin)/hs
            m(2) = spg
            m(3) = max(0.0_dp, -pmin)/p_mean
        case default
            m = huge(1.0_dp)
        end select
    end function law_measures

    include 'veslide_contact_law_maps.inc'

end module veslide_contact_law
