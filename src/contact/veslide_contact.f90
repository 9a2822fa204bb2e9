!> The load-controlled periodic contact problem of a rigid surface on a half-space, and the one
!> residual definition every solver reports.
!>
!> Find p with mean(p) = p_mean, and an approach d, such that the gap g = K p - h + d and p
!> obey the problem's contact law (`law`, veslide_contact_law; the hard wall: p >= 0, g >= 0 and
!> p g = 0 everywhere). K is the kernel (zero on the mean mode), h the heights with their mean
!> removed; d is then the mean gap over the contact set (the law's contact cells). The problem
!> keeps the heights as given with their mean beside them and centres them where they are used
!> (h - h_mean, the same rounding as a centred copy), so that it can hold the case's own array.
!>
!> Residual (`residual_measures`): max(penetration, complementarity, negative pressure, load error),
!> the first three the law's measures (`contact_law_t%measures`; the hard wall:
!>   penetration = max(-g)/h_s, complementarity = |sum p g|/(sum p * h_s),
!>   negative pressure = max(-p)/p_mean), load error = |mean p - p_mean|/p_mean,
!> h_s = rms height (or the displacement scale p_mean*max|K| for a flat surface), always evaluated
!> on a freshly computed K p before a solver reports convergence.
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
    use veslide_arrays, only: rarray_t, carray_t
    use veslide_transform, only: transform_t
    use veslide_passes, only: multiply_spectrum
    use veslide_contact_passes, only: gap_and_contact_sums, gap_measures, project_and_sum, adhesive_measures
    use veslide_passes, only: fill, scale
    use veslide_contact_law, only: contact_law_t, ADH_STRESS
    use veslide_device, only: device_check
    use veslide_clock, only: wall_seconds
    implicit none
    private
    public :: contact_problem_t, contact_state_t, contact_fields_t, new_contact_problem, new_contact_problem_moving, &
              residual_measures

    !> One contact problem: the operator, the heights, the load and the contact law
    type :: contact_problem_t
        type(kernel_t) :: kernel                   !! the influence operator
        type(contact_law_t) :: law                 !! the contact law (default: the hard wall)
        real(dp), allocatable :: h(:, :)           !! heights as given (any mean) [m]
        real(dp) :: h_mean = 0.0_dp                !! their mean; the problem's heights are h - h_mean [m]
        real(dp) :: p_mean_pa = 0.0_dp             !! nominal pressure [Pa] (tensile below 0: adhesive laws)
        !> the residual's unit of pressure [Pa]: p_mean for the hard wall, max(|p_mean|, sigma0)
        !> for an adhesive law (whose load may be zero or tensile)
        real(dp) :: p_scale_pa = 0.0_dp
        real(dp) :: height_scale_m = 0.0_dp        !! h_s of the residual [m]
        !> approach control: the mean gap d is given (`mean_gap_m`) and the load follows (the
        !> adhesive laws' solver only, veslide_solver_gcg; p_mean_pa is then its first guess)
        logical :: approach_control = .false.
        real(dp) :: mean_gap_m = 0.0_dp            !! the given mean gap d [m] (approach control)
    contains
        procedure :: grid => problem_grid
        procedure :: residuals => problem_residuals
        procedure :: residuals_on => problem_residuals_on
        procedure :: start => problem_start
        procedure :: fields => problem_fields
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
        !> the unit of the residuals [Pa]: the problem's pressure scale (p_mean; with an adhesive
        !> law the larger of |p_mean| and the law's largest attraction)
        real(dp) :: p_scale_pa = 0.0_dp
        !> where the solver's own residual stalled at its round-off, in units of the problem's
        !> pressure scale ('gcg': the adhesive gradient's largest entry); 0 where it did not
        real(dp) :: round_off = 0.0_dp
        !> gcg's splitting retuned its mean mode's metric (docs/adhesion.md, *Sliding*)
        logical :: mean_metric_retuned = .false.
        !> gcg's splitting: the inner steps that clipped a few cells and kept the conjugacy
        !> (docs/adhesion.md, *Sliding*)
        integer :: kept_conjugacy_steps = 0
        character(len=:), allocatable :: method  !! name of the method used
        character(len=3) :: device = 'cpu'      !! where it was solved: 'cpu' or 'gpu'
        !> on the device: the time of its set-up (memory, cuFFT plans), uploads and downloads [s]
        real(dp) :: transfer_seconds = 0.0_dp
    end type contact_state_t

    !> The arrays of one solve, where it runs: on the host views of the problem's heights, the
    !> kernel's multiplier, the state's fields and the caller's FFT buffers (nothing copied); on
    !> the device their copies there, made once by `problem%fields` (heights, multiplier and
    !> the starting pressure go in) and read back by `finish` (p, u and g come out)
    type :: contact_fields_t
        logical :: device = .false.
        type(transform_t) :: t                    !! the FFT and its buffers t%x, t%k
        type(rarray_t) :: h                       !! heights as given [m]
        type(carray_t) :: kd                      !! the kernel's multiplier K_d [m/Pa]
        type(rarray_t) :: p, u, g                 !! the state's pressure, displacement, gap
        !> device: g holds the gap of the start (the previous case of a study, kept there:
        !> solve_contact's `keep`), which the solvers take instead of uploading g_init
        logical :: gap_held = .false.
    contains
        procedure :: finish => fields_finish
        procedure :: apply_kernel => fields_apply_kernel
    end type contact_fields_t

contains

    !> The problem of heights `h` (any mean) under nominal pressure `p_mean` with operator `kernel`
    !> and the contact law `law` (default: the hard wall)
    subroutine new_contact_problem(self, kernel, h, p_mean, error, law)
        type(contact_problem_t), intent(out) :: self
        type(kernel_t), intent(in) :: kernel
        real(dp), intent(in) :: h(:, :)
        real(dp), intent(in) :: p_mean
        type(error_t), allocatable, intent(out) :: error
        type(contact_law_t), intent(in), optional :: law
        if (present(law)) self%law = law
        call check_problem(kernel, h, p_mean, self%law%adhesive(), error); if (allocated(error)) return
        self%kernel = kernel
        self%h = h
        call set_mean_and_load(self, p_mean)
    end subroutine new_contact_problem

    !> The same, the problem taking `kernel`'s multiplier and the array `h` instead of copies of
    !> them (16 bytes per cell fewer while it lives); `problem%release(kernel, h)` gives them back
    !> unchanged. On an error both are kept.
    subroutine new_contact_problem_moving(self, kernel, h, p_mean, error, law)
        type(contact_problem_t), intent(out) :: self
        type(kernel_t), intent(inout) :: kernel
        real(dp), allocatable, intent(inout) :: h(:, :)
        real(dp), intent(in) :: p_mean
        type(error_t), allocatable, intent(out) :: error
        type(contact_law_t), intent(in), optional :: law
        if (present(law)) self%law = law
        call check_problem(kernel, h, p_mean, self%law%adhesive(), error); if (allocated(error)) return
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

    subroutine check_problem(kernel, h, p_mean, adhesive, error)
        type(kernel_t), intent(in) :: kernel
        real(dp), intent(in) :: h(:, :)
        real(dp), intent(in) :: p_mean
        !> the law attracts: any finite load (tensile ones too)
        logical, intent(in) :: adhesive
        type(error_t), allocatable, intent(out) :: error
        logical :: nan
        if (any(shape(h) /= kernel%grid%local_shape())) then
            call fatal_error(error, "veslide:contact:new_contact_problem: heights and kernel grids differ"); return
        end if
        if (adhesive) then
            if (.not. (abs(p_mean) <= huge(1.0_dp))) then
                call fatal_error(error, "veslide:contact:new_contact_problem: the nominal pressure must be finite"); return
            end if
        else if (.not. (p_mean > 0.0_dp)) then
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
            self%p_scale_pa = p_mean
            if (self%law%adhesive()) self%p_scale_pa = max(abs(p_mean), self%law%param(ADH_STRESS))
            self%h_mean = field_mean(grid, self%h)
            self%height_scale_m = field_rms(grid, self%h)
        end associate
        if (self%height_scale_m <= 0.0_dp) self%height_scale_m = self%p_scale_pa*self%kernel%max_abs()
        if (self%height_scale_m <= 0.0_dp) self%height_scale_m = 1.0_dp
    end subroutine set_mean_and_load

    pure function problem_grid(self) result(grid)
        class(contact_problem_t), intent(in) :: self
        type(grid_t) :: grid
        grid = self%kernel%grid
    end function problem_grid

    !> A fresh state: fields allocated, pressure uniform or from `p_init` (made admissible by the
    !> law's proximal map, clipped at zero for the hard wall, and rescaled to the load)
    subroutine problem_start(self, state, p_init, factor)
        class(contact_problem_t), intent(in) :: self
        type(contact_state_t), intent(out) :: state
        real(dp), intent(in), optional :: p_init(:, :)
        !> the start is law%project(p_init) times `factor` (0: the uniform pressure)
        real(dp), intent(out), optional :: factor
        integer :: nx, ny
        real(dp) :: total, f
        integer :: j
        if (present(factor)) factor = 0.0_dp
        nx = size(self%h, 1); ny = size(self%h, 2)
        allocate (state%p(nx, ny), state%u(nx, ny), state%g(nx, ny))
        !$omp parallel do schedule(static)
        do j = 1, ny
            state%p(:, j) = self%p_mean_pa
        end do
        !$omp end parallel do
        if (present(p_init) .and. .not. self%law%adhesive()) then
            if (all(shape(p_init) == [nx, ny])) then
                total = field_sum(self%kernel%grid, self%law%project(p_init))
                if (total > 0.0_dp) then
                    f = self%p_mean_pa*self%kernel%grid%cells()/total
                    state%p = self%law%project(p_init)
                    state%p = state%p*f
                    if (present(factor)) factor = f
                end if
            end if
        end if
    end subroutine problem_start

    !> The four measures and the residual from sums over the grid: min gap `gmin`, sum(p g) `spg`,
    !> sum(|p|) `sp`, min pressure `pmin`, sum(p) `sum_p` over `n` points (the one definition):
    !> the law's three measures and the load error
    pure subroutine residual_measures(law, state, gmin, spg, sp, pmin, sum_p, n, p_mean, hs, p_scale)
        type(contact_law_t), intent(in) :: law
        type(contact_state_t), intent(inout) :: state
        real(dp), intent(in) :: gmin, spg, sp, pmin, sum_p, n, p_mean, hs
        !> the unit of pressure (default p_mean; an adhesive law's problem%p_scale_pa)
        real(dp), intent(in), optional :: p_scale
        real(dp) :: m(3), ps
        ps = p_mean
        if (present(p_scale)) ps = p_scale
        m = law%measures(gmin, spg, sp, pmin, hs, ps)
        state%penetration = m(1)
        state%complementarity = m(2)
        state%negative_pressure = m(3)
        state%load_error = abs(sum_p/n - p_mean)/ps
        state%residual = max(state%penetration, state%complementarity, state%negative_pressure, state%load_error)
    end subroutine residual_measures

    !> The arrays of a solve of this problem from `state` (its start in state%p) with the FFT
    !> `fft`: views of them (`device` false), or copies on the device with its own transforms
    !> (collective on a distributed grid, which the device refuses). `self`, `state` and `fft`
    !> must stay where they are while the fields live.
    subroutine problem_fields(self, f, fft, state, device, error, kept_start, same_heights)
        class(contact_problem_t), intent(in), target :: self
        !> the fields (made anew; on the device, where `kept_start` is given and they are the
        !> previous case's of the grid, kept there)
        type(contact_fields_t), intent(inout) :: f
        type(fft2d_t), intent(inout), target :: fft
        type(contact_state_t), intent(inout), target :: state
        logical, intent(in) :: device
        type(error_t), allocatable, intent(out) :: error
        !> a study's next case on the device: its start is law%project of the pressure `f` holds
        !> (the previous case's) times `kept_start` (0: the uniform pressure; problem%start's
        !> factor), and g_init is the gap `f` holds; only the multiplier goes up, and the heights
        !> unless `same_heights`
        real(dp), intent(in), optional :: kept_start
        logical, intent(in), optional :: same_heights
        integer :: nx, ny
        real(dp) :: t0
        real(dp), allocatable :: rows(:)
        logical :: kept
        nx = size(self%h, 1); ny = size(self%h, 2)
        kept = device .and. f%device .and. present(kept_start)
        if (kept) kept = f%p%n1 == nx .and. f%p%n2 == ny .and. .not. self%kernel%grid%is_distributed()
        if (.not. kept) call f%finish()
        f%gap_held = .false.
        if (kept) then
            ! the previous case's fields: the start formed where it is (the host's operations on
            ! the same values: the same bits), the multiplier (and new heights) up
            t0 = wall_seconds()
            if (present(same_heights)) then
                if (.not. same_heights) call f%h%upload(self%h)
            else
                call f%h%upload(self%h)
            end if
            call self%kernel%multiplier_array(f%kd, .true.)
            if (self%law%adhesive()) then
                ! (an adhesive law's solver starts from the gap alone: p is not read)
            else if (kept_start > 0.0_dp) then
                allocate (rows(ny))
                call project_and_sum(self%law, f%p, rows)
                call scale(f%p, kept_start)
            else
                call fill(f%p, self%p_mean_pa)
            end if
            f%gap_held = .true.
            call f%t%lend_work(f%u)
            call device_check(error, "veslide:contact:fields")
            if (allocated(error)) call f%finish()
            state%transfer_seconds = wall_seconds() - t0
            return
        end if
        f%device = device
        if (.not. device) then
            call f%t%on_host(fft)
            call f%h%view(self%h)
            call self%kernel%multiplier_array(f%kd, .false.)
            call f%p%view(state%p); call f%u%view(state%u); call f%g%view(state%g)
            return
        end if
        if (self%kernel%grid%is_distributed()) then
            call fatal_error(error, "veslide:contact:fields: a grid distributed over processes cannot be solved on"// &
                             " a device (an MPI study gives each rank its own)"); return
        end if
        t0 = wall_seconds()
        call f%t%on_device(nx, ny, error); if (allocated(error)) return
        call f%h%create(nx, ny, .true.); call f%h%upload(self%h)
        call self%kernel%multiplier_array(f%kd, .true.)
        call f%p%create(nx, ny, .true.); call f%p%upload(state%p)
        ! cuFFT's work area in u (at most 8 bytes per cell, measured: u's size; u is made as large
        ! should a plan need more): u = K p is formed after the transforms that make it
        ! (apply_kernel) and read by no solver across a transform (one that does, pdr with
        ! Anderson mixing, gives the transform its own: lend_work)
        call f%u%create(nx, ny, .true., at_least=int(f%t%work_bytes, i8)); call f%g%create(nx, ny, .true.)
        call f%t%lend_work(f%u)
        call device_check(error, "veslide:contact:fields")
        if (allocated(error)) call f%finish()
        state%transfer_seconds = wall_seconds() - t0
    end subroutine problem_fields

    !> The fields done with: on the device p, u and g read back into `state` (when given) and
    !> the device memory freed (but with `keep`: kept for a study's next case, problem%fields's
    !> `kept_start`); on the host the views dropped
    subroutine fields_finish(self, state, keep)
        class(contact_fields_t), intent(inout) :: self
        type(contact_state_t), intent(inout), optional :: state
        logical, intent(in), optional :: keep
        real(dp) :: t0
        if (self%device .and. present(state)) then
            t0 = wall_seconds()
            call self%p%download(state%p); call self%u%download(state%u); call self%g%download(state%g)
            state%transfer_seconds = state%transfer_seconds + (wall_seconds() - t0)
        end if
        self%gap_held = .false.
        if (present(keep)) then
            if (keep .and. self%device) return
        end if
        self%device = .false.
        call self%t%destroy()
        call self%h%destroy(); call self%kd%destroy()
        call self%p%destroy(); call self%u%destroy(); call self%g%destroy()
    end subroutine fields_finish

    !> dst = K src (zero mean), through the FFT's buffers (one FFT pair; t%k overwritten)
    subroutine fields_apply_kernel(self, src, dst, cells)
        class(contact_fields_t), intent(inout) :: self
        type(rarray_t), intent(in) :: src
        type(rarray_t), intent(inout) :: dst
        real(dp), intent(in) :: cells    !! the whole grid's cells (FFTW's normalisation)
        call self%t%x%assign(src)
        call self%t%forward()
        ! one fused pass (an array expression here made a temporary of K_d/N on every call)
        call multiply_spectrum(self%t%k, self%kd, 1.0_dp/cells)
        call self%t%backward_unscaled()
        call dst%assign(self%t%x)
    end subroutine fields_apply_kernel

    !> The verdict on a solver's result, on the number reported: u = K p computed afresh, the
    !> residual measured, and converged exactly when that residual is <= tolerance (one FFT pair).
    !> Every solver confirms through this before it reports convergence, and `solve_contact`
    !> gives the final verdict with it.
    subroutine problem_confirm(self, f, state, tolerance)
        class(contact_problem_t), intent(in) :: self
        type(contact_fields_t), intent(inout) :: f
        type(contact_state_t), intent(inout) :: state
        real(dp), intent(in) :: tolerance
        call f%apply_kernel(f%p, f%u, self%kernel%grid%cells())
        state%operator_applications = state%operator_applications + 1
        call self%residuals_on(f, state)
        state%converged = state%residual <= tolerance
    end subroutine problem_confirm

    !> Residuals of a candidate (p, u = K p) held in `state` on the host: fills d (the
    !> contact-set mean of h - u), g and the four measures of `state`
    subroutine problem_residuals(self, state)
        class(contact_problem_t), intent(in), target :: self
        type(contact_state_t), intent(inout), target :: state
        type(contact_fields_t) :: f
        call f%h%view(self%h)
        call f%p%view(state%p); call f%u%view(state%u); call f%g%view(state%g)
        call self%residuals_on(f, state)
        call f%finish()
    end subroutine problem_residuals

    !> Residuals of a candidate (p, u = K p) held in the fields `f`: g there, d and the four
    !> measures in `state` (two passes over the grid)
    subroutine problem_residuals_on(self, f, state)
        class(contact_problem_t), intent(in) :: self
        type(contact_fields_t), intent(inout) :: f
        type(contact_state_t), intent(inout) :: state
        integer(i8) :: nc(1)
        real(dp) :: rows(3, f%g%n2), t(3), ext(2), gmax
        if (self%law%adhesive()) then
            call adhesive_residuals(self, f, state); return
        end if
        associate (grid => self%kernel%grid)
            call gap_and_contact_sums(self%law, f%u, f%h, self%h_mean, f%p, f%g, rows(1, :), nc(1), gmax)
            call global_count(grid, nc)
            if (nc(1) > 0) then
                call ordered_sum(grid, rows(1:1, :), t(1:1))
                state%approach_m = -t(1)/real(nc(1), dp)
            else
                t(1) = gmax
                call global_max(grid, t(1))
                state%approach_m = -t(1)
            end if
            call gap_measures(self%law, f%p, f%g, state%approach_m, rows, ext(1), ext(2))
            call ordered_sum(grid, rows, t)
            call global_min(grid, ext)
            call residual_measures(self%law, state, ext(1), t(1), t(2), ext(2), t(3), grid%cells(), self%p_mean_pa, &
                                   self%height_scale_m)
        end associate
    end subroutine problem_residuals_on

    !> Residuals of a candidate of an adhesive law on the fields `f`: p with u = K p fresh,
    !> the solver's gap g_s in f%g (its closed cells exactly 0) and approach in state%approach_m.
    !> The gap g = u - h + d is formed afresh; the law's measures take the repulsive pressure
    !> p_rep = p + sigma(g_s) (at the solver's gap: a law with a jump, Dugdale's, would flip at
    !> round-off on the fresh one) with the fresh gap, whose distance from the solver's counts as
    !> penetration (max(-g, |g - g_s|)/h_s); the complementarity cell by cell,
    !> max min(|p_rep|/p_s, g/h_s). The gap kept is the fresh one on the open cells (at
    !> least 0) and 0 on the cells the solver closed, which stay the contact
    subroutine adhesive_residuals(self, f, state)
        class(contact_problem_t), intent(in) :: self
        type(contact_fields_t), intent(inout) :: f
        type(contact_state_t), intent(inout) :: state
        real(dp) :: rows(1, f%g%n2), sum_p(1), ext(2), c
        call adhesive_measures(self%law, f%u, f%h, self%h_mean, f%p, f%g, state%approach_m, self%p_scale_pa, &
                               self%height_scale_m, rows(1, :), ext, c)
        call ordered_sum(self%kernel%grid, rows, sum_p)
        call global_min(self%kernel%grid, ext)
        ! the complementarity cell by cell (contact_law_t%measures; no sum of |p_rep| is needed)
        call global_max(self%kernel%grid, c)
        ! (under approach control the load is the result: no load error)
        call residual_measures(self%law, state, ext(1), c, 0.0_dp, ext(2), sum_p(1), self%kernel%grid%cells(), &
                               merge(sum_p(1)/self%kernel%grid%cells(), self%p_mean_pa, self%approach_control), &
                               self%height_scale_m, self%p_scale_pa)
    end subroutine adhesive_residuals

end module veslide_contact
