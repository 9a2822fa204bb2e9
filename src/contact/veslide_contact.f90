!> The load-controlled periodic contact problem of a rigid surface on a half-space, and the one
!> residual definition every solver reports.
!>
!> Find p >= 0 with mean(p) = p_mean, and an approach d, such that the gap
!> g = K p - h + d >= 0 and p g = 0 everywhere. K is the kernel (zero on the mean mode), h the
!> heights with their mean removed; d is then the mean gap (the mean separation). The problem
!> keeps the heights as given with their mean beside them and centres them where they are used
!> (h - h_mean, the same rounding as a centred copy), so that it can hold the case's own array.
!>
!> Residual (`residual_measures`): max(penetration, complementarity, negative pressure, load error),
!>   penetration = max(-g)/h_s, complementarity = |sum p g|/(sum p * h_s),
!>   negative pressure = max(-p)/p_mean, load error = |mean p - p_mean|/p_mean,
!> h_s = rms height (or the displacement scale p_mean*max|K| for a flat surface), always evaluated
!> on a freshly computed K p before a solver reports convergence. A new contact law (adhesion, a
!> different constraint) is a new projection in the solvers and new measures here.
!> Fields are the process's rows (nx, ny_local) of the kernel's grid; every sum, extremum and
!> count is over the whole grid (veslide_collective), so every process takes the same decisions.
module veslide_contact
    use veslide_kinds, only: dp, i8
    use veslide_error, only: error_t, fatal_error
    use veslide_grid, only: grid_t
    use veslide_kernel, only: kernel_t
    use veslide_fftw, only: fft2d_t
    use veslide_collective, only: ordered_sum, global_min, global_max, global_count, global_any
    use veslide_fields, only: field_mean, field_rms, field_sum
    implicit none
    private
    public :: contact_problem_t, contact_state_t, new_contact_problem, new_contact_problem_moving, residual_measures

    !> One contact problem: the operator, the heights and the load
    type :: contact_problem_t
        type(kernel_t) :: kernel                   !! the influence operator
        real(dp), allocatable :: h(:, :)           !! heights as given (any mean) [m]
        real(dp) :: h_mean = 0.0_dp                !! their mean; the problem's heights are h - h_mean [m]
        real(dp) :: p_mean_pa = 0.0_dp             !! nominal pressure [Pa]
        real(dp) :: height_scale_m = 0.0_dp        !! h_s of the residual [m]
    contains
        procedure :: grid => problem_grid
        procedure :: residuals => problem_residuals
        procedure :: start => problem_start
        procedure :: confirm => problem_confirm
        procedure :: release => problem_release
    end type contact_problem_t

    !> A candidate or final solution with its residuals and the work spent
    type :: contact_state_t
        real(dp), allocatable :: p(:, :)        !! pressure [Pa]
        real(dp), allocatable :: u(:, :)        !! zero-mean displacement K p, positive into the solid [m]
        real(dp), allocatable :: g(:, :)        !! gap [m], >= 0 up to the tolerance
        real(dp) :: approach_m = 0.0_dp         !! d: the mean gap [m]
        integer :: iterations = 0
        integer :: operator_applications = 0    !! FFT pairs spent on K
        logical :: converged = .false.
        real(dp) :: penetration = huge(1.0_dp), complementarity = huge(1.0_dp)
        real(dp) :: negative_pressure = huge(1.0_dp), load_error = huge(1.0_dp)
        real(dp) :: residual = huge(1.0_dp)
        character(len=:), allocatable :: method  !! name of the method used
    end type contact_state_t

contains

    !> The problem of heights `h` (any mean) under nominal pressure `p_mean` with operator `kernel`
    subroutine new_contact_problem(self, kernel, h, p_mean, error)
        type(contact_problem_t), intent(out) :: self
        type(kernel_t), intent(in) :: kernel
        real(dp), intent(in) :: h(:, :)
        real(dp), intent(in) :: p_mean
        type(error_t), allocatable, intent(out) :: error
        call check_problem(kernel, h, p_mean, error); if (allocated(error)) return
        self%kernel = kernel
        self%h = h
        call set_mean_and_load(self, p_mean)
    end subroutine new_contact_problem

    !> The same, the problem taking `kernel`'s multiplier and the array `h` instead of copies of
    !> them (16 bytes per cell fewer while it lives); `problem%release(kernel, h)` gives them back
    !> unchanged. On an error both are kept.
    subroutine new_contact_problem_moving(self, kernel, h, p_mean, error)
        type(contact_problem_t), intent(out) :: self
        type(kernel_t), intent(inout) :: kernel
        real(dp), allocatable, intent(inout) :: h(:, :)
        real(dp), intent(in) :: p_mean
        type(error_t), allocatable, intent(out) :: error
        call check_problem(kernel, h, p_mean, error); if (allocated(error)) return
        call kernel%move_to(self%kernel)
        call move_alloc(h, self%h)
        call set_mean_and_load(self, p_mean)
    end subroutine new_contact_problem_moving

    !> The kernel and the heights back to where new_contact_problem_moving took them from (the
    !> problem is left without)
    subroutine problem_release(self, kernel, h)
        class(contact_problem_t), intent(inout) :: self
        type(kernel_t), intent(out) :: kernel
        real(dp), allocatable, intent(out) :: h(:, :)
        call self%kernel%move_to(kernel)
        call move_alloc(self%h, h)
    end subroutine problem_release

    subroutine check_problem(kernel, h, p_mean, error)
        type(kernel_t), intent(in) :: kernel
        real(dp), intent(in) :: h(:, :)
        real(dp), intent(in) :: p_mean
        type(error_t), allocatable, intent(out) :: error
        logical :: nan
        if (any(shape(h) /= kernel%grid%local_shape())) then
            call fatal_error(error, "veslide:contact:new_contact_problem: heights and kernel grids differ"); return
        end if
        if (.not. (p_mean > 0.0_dp)) then
            call fatal_error(error, "veslide:contact:new_contact_problem: the nominal pressure must be positive"); return
        end if
        nan = any(h /= h)
        call global_any(kernel%grid, nan)
        if (nan) then
            call fatal_error(error, "veslide:contact:new_contact_problem: the heights contain NaN"); return
        end if
    end subroutine check_problem

    !> The heights' mean, the load and the height scale h_s of the residual
    subroutine set_mean_and_load(self, p_mean)
        type(contact_problem_t), intent(inout) :: self
        real(dp), intent(in) :: p_mean
        associate (grid => self%kernel%grid)
            self%p_mean_pa = p_mean
            self%h_mean = field_mean(grid, self%h)
            self%height_scale_m = field_rms(grid, self%h)
        end associate
        if (self%height_scale_m <= 0.0_dp) self%height_scale_m = p_mean*self%kernel%max_abs()
        if (self%height_scale_m <= 0.0_dp) self%height_scale_m = 1.0_dp
    end subroutine set_mean_and_load

    pure function problem_grid(self) result(grid)
        class(contact_problem_t), intent(in) :: self
        type(grid_t) :: grid
        grid = self%kernel%grid
    end function problem_grid

    !> A fresh state: fields allocated, pressure uniform or from `p_init` (clipped at zero and
    !> rescaled to the load)
    subroutine problem_start(self, state, p_init)
        class(contact_problem_t), intent(in) :: self
        type(contact_state_t), intent(out) :: state
        real(dp), intent(in), optional :: p_init(:, :)
        integer :: nx, ny
        real(dp) :: total
        nx = size(self%h, 1); ny = size(self%h, 2)
        allocate (state%p(nx, ny), state%u(nx, ny), state%g(nx, ny))
        state%p = self%p_mean_pa
        if (present(p_init)) then
            if (all(shape(p_init) == [nx, ny])) then
                total = field_sum(self%kernel%grid, max(p_init, 0.0_dp))
                if (total > 0.0_dp) then
                    state%p = max(p_init, 0.0_dp)
                    state%p = state%p*(self%p_mean_pa*self%kernel%grid%cells()/total)
                end if
            end if
        end if
    end subroutine problem_start

    !> The four measures and the residual from sums over the grid: min gap `gmin`, sum(p g) `spg`,
    !> sum(|p|) `sp`, min pressure `pmin`, sum(p) `sum_p` over `n` points (the one definition)
    pure subroutine residual_measures(state, gmin, spg, sp, pmin, sum_p, n, p_mean, hs)
        type(contact_state_t), intent(inout) :: state
        real(dp), intent(in) :: gmin, spg, sp, pmin, sum_p, n, p_mean, hs
        state%penetration = max(0.0_dp, -gmin)/hs
        state%complementarity = abs(spg)/(sp*hs)
        state%negative_pressure = max(0.0_dp, -pmin)/p_mean
        state%load_error = abs(sum_p/n - p_mean)/p_mean
        state%residual = max(state%penetration, state%complementarity, state%negative_pressure, state%load_error)
    end subroutine residual_measures

    !> The verdict on a solver's result, on the number reported: u = K p computed afresh, the
    !> residual measured, and converged exactly when that residual is <= tolerance (one FFT pair)
    subroutine problem_confirm(self, fft, state, tolerance)
        class(contact_problem_t), intent(in) :: self
        type(fft2d_t), intent(inout) :: fft
        type(contact_state_t), intent(inout) :: state
        real(dp), intent(in) :: tolerance
        call self%kernel%apply(fft, state%p, state%u)
        state%operator_applications = state%operator_applications + 1
        call self%residuals(state)
        state%converged = state%residual <= tolerance
    end subroutine problem_confirm

    !> Residuals of a candidate (p, u = K p): fills d (the contact-set mean of h - u), g and the
    !> four measures of `state`
    subroutine problem_residuals(self, state)
        class(contact_problem_t), intent(in) :: self
        type(contact_state_t), intent(inout) :: state
        integer(i8) :: nc(1)
        integer :: j
        real(dp) :: rows(3, size(state%p, 2)), t(3), ext(2)
        associate (grid => self%kernel%grid)
            nc(1) = count(state%p > 0.0_dp, kind=i8)
            call global_count(grid, nc)
            state%g = state%u - (self%h - self%h_mean)
            if (nc(1) > 0) then
                do j = 1, size(state%p, 2)
                    rows(1, j) = sum(state%g(:, j), mask=state%p(:, j) > 0.0_dp)
                end do
                call ordered_sum(grid, rows(1:1, :), t(1:1))
                state%approach_m = -t(1)/real(nc(1), dp)
            else
                t(1) = -huge(1.0_dp); if (size(state%g) > 0) t(1) = maxval(state%g)
                call global_max(grid, t(1))
                state%approach_m = -t(1)
            end if
            state%g = state%g + state%approach_m
            !$omp parallel do schedule(guided)
            do j = 1, size(state%p, 2)
                rows(:, j) = [sum(state%p(:, j)*state%g(:, j)), sum(abs(state%p(:, j))), sum(state%p(:, j))]
            end do
            !$omp end parallel do
            call ordered_sum(grid, rows, t)
            ext = huge(1.0_dp)
            if (size(state%p) > 0) ext = [minval(state%g), minval(state%p)]
            call global_min(grid, ext)
            call residual_measures(state, ext(1), t(1), t(2), ext(2), t(3), grid%cells(), self%p_mean_pa, &
                                   self%height_scale_m)
        end associate
    end subroutine problem_residuals

end module veslide_contact
