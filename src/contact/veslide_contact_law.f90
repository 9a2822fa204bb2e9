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
!> One law today: the hard wall (`LAW_HARD_WALL`, Signorini's conditions) p >= 0, g >= 0,
!> p g = 0, contact where p > 0, without parameters. A pass takes the law whole and chooses its
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
    use veslide_kinds, only: dp
    use veslide_strings, only: name_index
    implicit none
    private
    public :: contact_law_t, law_id, law_names, law_count, law_max_params, LAW_HARD_WALL
    public :: hard_wall_project, hard_wall_in_contact, hard_wall_in_contact_shifted, hard_wall_below, &
              hard_wall_penetrates

    integer, parameter :: LAW_HARD_WALL = 1
    !> The laws there are (LAW_* ids 1..law_count)
    integer, parameter :: law_count = 1
    !> Names of the laws, indexed by their LAW_* id
    character(len=*), parameter :: law_names(law_count) = [character(len=9) :: 'hard_wall']
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
    end type contact_law_t

contains

    !> LAW_* id from a law's name; 0 when unknown
    pure integer function law_id(name) result(id)
        character(len=*), intent(in) :: name
        id = name_index(name, law_names)
    end function law_id

    !> The law's name
    pure function law_name(self) result(name)
        class(contact_law_t), intent(in) :: self
        character(len=:), allocatable :: name
        name = 'unknown'
        if (self%kind >= 1 .and. self%kind <= law_count) name = trim(law_names(self%kind))
    end function law_name

    !> The contact cells of the pressure field `p`: where the law says a cell is in contact
    pure function law_contact(self, p) result(yes)
        class(contact_law_t), intent(in) :: self
        real(dp), intent(in) :: p(:, :)
        logical :: yes(size(p, 1), size(p, 2))
        select case (self%kind)
        case (LAW_HARD_WALL)
            yes = hard_wall_in_contact(p)
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
    !> nominal pressure `p_mean`. Returns [penetration, complementarity, negative pressure]; for the
    !> hard wall max(-g)/h_s, |sum p g|/(sum p * h_s) and max(-p)/p_mean (veslide_contact)
    pure function law_measures(self, gmin, spg, sp, pmin, hs, p_mean) result(m)
        class(contact_law_t), intent(in) :: self
        real(dp), intent(in) :: gmin, spg, sp, pmin, hs, p_mean
        real(dp) :: m(3)
        select case (self%kind)
        case (LAW_HARD_WALL)
            m(1) = max(0.0_dp, -gmin)/hs
            m(2) = abs(spg)/(sp*hs)
            m(3) = max(0.0_dp, -pmin)/p_mean
        case default
            m = huge(1.0_dp)
        end select
    end function law_measures

    include 'veslide_contact_law_maps.inc'

end module veslide_contact_law
