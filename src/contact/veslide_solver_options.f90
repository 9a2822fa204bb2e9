!> The knobs of the contact solvers and the names of the methods
module veslide_solver_options
    use veslide_kinds, only: dp
    use veslide_strings, only: name_index
    implicit none
    private
    public :: solver_options_t, solver_method_id, solver_method_names
    public :: SOLVER_AUTO, SOLVER_PK, SOLVER_DR, SOLVER_BCCG, SOLVER_PDR

    integer, parameter :: SOLVER_AUTO = 1, SOLVER_PK = 2, SOLVER_DR = 3, SOLVER_BCCG = 4, SOLVER_PDR = 5
    !> Names of the methods, indexed by their SOLVER_* id (the namelist's `&solver method`)
    character(len=*), parameter :: solver_method_names(5) = [character(len=4) :: 'auto', 'pk', 'dr', 'bccg', &
                                                             'pdr']

    type :: solver_options_t
        integer :: method = SOLVER_AUTO         !! SOLVER_* id
        real(dp) :: tolerance = 1.0e-10_dp      !! target of the residual [-]
        integer :: max_iterations = 20000       !! iteration cap
        integer :: refresh_every = 200          !! recompute K p exactly this often (pk)
        integer :: anderson_memory = 5          !! Anderson mixing depth (dr); 0 switches it off
        integer :: balance_every = 100          !! step-size balancing interval (dr; docs/solver-scaling.md)
        real(dp) :: step = 0.0_dp               !! initial dimensionless step (dr); 0: automatic
        real(dp) :: balance_ratio = 10.0_dp     !! imbalance of the residuals that changes the step (dr)
        real(dp) :: balance_factor = 3.0_dp     !! factor the step changes by (dr)
    end type solver_options_t

contains

    !> SOLVER_* id from a method name; 0 when unknown
    pure integer function solver_method_id(name) result(id)
        character(len=*), intent(in) :: name
        id = name_index(name, solver_method_names)
    end function solver_method_id

end module veslide_solver_options
