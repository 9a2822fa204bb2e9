!> The device path. Which tests run depends on the build:
!>  - without a usable device (the CPU build, or the GPU build where no GPU is visible): 'gpu' is
!>    refused with a message naming the choices, and 'auto' solves on the CPU;
!>  - with one (a GPU, or the emulated device of `gpu/build.sh --emulate`): every device pass
!>    against its CPU twin on random data (1e-13 relative), the cuFFT twin against FFTW, dense
!>    references and hard cases solved on the device, the device against the CPU on the same
!>    cases (pressure, area, friction, lateral force to 1e-10; FFT pairs within 2 %), a solve
!>    repeated bit for bit, the refusals of what the device does not run, and its memory count;
!>    the adhesive laws' solver (gcg) pass by pass and against the CPU on the hard scenes.
module test_veslide_device
    use, intrinsic :: iso_fortran_env, only: int8, real32
    use, intrinsic :: iso_c_binding, only: c_int
    use veslide_kinds, only: dp, i8
    use veslide_strings, only: str
    use veslide_error, only: fatal_error
    use veslide_grid, only: grid_t, new_grid
    use veslide_fftw, only: fft2d_t
    use veslide_device, only: device_enabled, device_count, device_emulated, device_info_t, device_info, &
                              device_peak_bytes, device_reset_peak, device_bytes_in_use, device_check, &
                              device_moved_bytes, device_has_room, device_download
    use veslide_arrays, only: rarray_t, carray_t, iarray_t, sarray_t
    use veslide_transform, only: transform_t
    use veslide_passes, only: fill, scale, divide, subtract, scaled_copy, divided_copy, centre_scale, centre_divide, &
                              row_sums, count_below, complex_scale, complex_add, complex_divide, &
                              multiply_spectrum
    use veslide_kernel_passes, only: resolvent_multiplier, resolvent_apply
    use veslide_contact_passes, only: gap_and_contact_sums, gap_measures, project_and_sum
    use veslide_contact_law, only: contact_law_t
    use veslide_bccg_passes, only: metric_t, metric, metric_values, set_contact, statistics, residual, precondition, &
                                   set_sum, direction, energy, step, &
                                   update_transform, step_transform, gap_multiply, add_points, clipped_points, &
                                   max_points
    use veslide_pdr_passes, only: step_constant, resolvent, scaled_product, residual_sums, residual_gap, relax, &
                                  add_scaled, full_contact, gap_to_z, sum_of, one_plus, difference_from
    use veslide_dr_passes, only: dr_rebalance, dr_project, dr_restore, dr_add_gap, dr_load_sums, dr_shift
    use veslide_anderson_passes, only: anderson_columns, anderson_update
    use veslide_gcg_passes, only: gcg_attract, gcg_free_set, gcg_centre, gcg_spectral, gcg_mask, gcg_dot, &
                                  gcg_shift_dot, gcg_direction, gcg_curvature, gcg_step, gcg_gap_sums, gcg_shift_open, &
                                  gcg_combine, gcg_extremes
    use veslide_contact_law, only: LAW_EXPONENTIAL, LAW_DUGDALE
    use veslide_material, only: material_t, new_elastic
    use veslide_kernel, only: kernel_t, new_kernel, KERNEL_SPECTRAL
    use veslide_contact, only: contact_problem_t, contact_state_t, new_contact_problem
    use veslide_solver_options, only: solver_options_t, solver_method_id, DEVICE_GPU, DEVICE_CPU, DEVICE_AUTO
    use veslide_solver, only: solve_contact, gpu_visible
    use veslide_config, only: config_t
    use veslide_case, only: case_t, run_case
    use veslide_memory, only: device_bytes_per_cell
    use veslide_study, only: run_study
    use veslide_scenes, only: hard_case_count, hard_case
    use test_veslide_hard, only: check_friction_sign, with_adhesion, has_warning
    use veslide_analysis, only: contact_area_fraction
    use testsuite, only: error_t, unittest_t, new_unittest, check, report
    use test_support, only: solve_case, unique_name, remove
    use dense_reference, only: dense_compare
    use reference_oracles, only: paper_rough, paper_solid, peak_speed
    implicit none
    private
    public :: collect_device, device_usable

    !> the tolerance of a device pass against its CPU twin: the same operations, summed in
    !> another order (and, for complex division, 1 ulp apart)
    real(dp), parameter :: pass_tol = 1.0e-13_dp
    integer, parameter :: nx = 48, ny = 20      ! a field not a multiple of the block (256)

contains

    !> Can this process solve on a device (a GPU, or the emulated one)?
    logical function device_usable()
        device_usable = device_enabled .and. device_count() > 0
    end function device_usable

    subroutine collect_device(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        if (.not. device_usable()) then
            tests = [ &
                new_unittest("gpu-refused-without-a-device", test_gpu_refused), &
                new_unittest("auto-solves-on-the-cpu", test_auto_cpu) &
                ]
            return
        end if
        tests = [ &
            new_unittest("device-info", test_info), &
            new_unittest("passes-shared", test_passes_shared), &
            new_unittest("passes-kernel-and-contact", test_passes_contact), &
            new_unittest("passes-bccg", test_passes_bccg), &
            new_unittest("passes-pdr", test_passes_pdr), &
            new_unittest("passes-dr-and-anderson", test_passes_dr), &
            new_unittest("passes-gcg", test_passes_gcg), &
            new_unittest("transform-against-fftw", test_transform), &
            new_unittest("dense-elastic-bccg", test_dense_bccg), &
            new_unittest("dense-visco-pdr", test_dense_pdr), &
            new_unittest("dense-visco-dr", test_dense_dr), &
            new_unittest("profile-one-row", test_profile), &
            new_unittest("hard-cases-on-the-device", test_hard), &
            new_unittest("device-against-cpu", test_against_cpu), &
            new_unittest("adhesive-scenes-against-cpu", test_adhesive_against_cpu), &
            new_unittest("adhesive-hard-cases-on-the-device", test_adhesive_hard), &
            new_unittest("repeats-bit-for-bit", test_repeat), &
            new_unittest("refusals", test_refusals), &
            new_unittest("memory-counted-and-returned", test_memory), &
            new_unittest("work-area-lent", test_work_area), &
            new_unittest("memory-estimate-is-the-peak", test_memory_estimate), &
            new_unittest("study-warm-start-stays-on-the-device", test_study_kept) &
            ]
    end subroutine collect_device

    ! ---- without a device ----------------------------------------------------------------

    subroutine test_gpu_refused(error)
        type(error_t), allocatable, intent(out) :: error
        type(contact_state_t) :: s
        real(dp) :: h(16, 16)
        character(len=:), allocatable :: msg
        call paper_rough(16, h, error); if (allocated(error)) return
        call solve_case(h, 0.01_dp, 0.01_dp, 1.0e5_dp, s, error, device='gpu')
        call refusal(error, msg, "device = 'gpu'"); if (allocated(error)) return
        call check(error, index(msg, "&solver device = 'gpu'") > 0 .and. index(msg, "'cpu'") > 0, &
                   "the refusal does not name the choice and the alternatives: "//msg)
    end subroutine test_gpu_refused

    subroutine test_auto_cpu(error)
        type(error_t), allocatable, intent(out) :: error
        type(contact_state_t) :: s
        real(dp) :: h(16, 16)
        call paper_rough(16, h, error); if (allocated(error)) return
        call solve_case(h, 0.01_dp, 0.01_dp, 1.0e5_dp, s, error, device='auto'); if (allocated(error)) return
        call check(error, s%device == 'cpu', "'auto' without a device solved on "//s%device)
        if (allocated(error)) return
        call check(error, .not. gpu_visible(), "'auto' finds a GPU where the suite found none")
    end subroutine test_auto_cpu

    ! ---- helpers -----------------------------------------------------------------------

    !> An expected refusal: its message in `msg` and the error cleared; none is an error
    subroutine refusal(error, msg, what)
        type(error_t), allocatable, intent(inout) :: error
        character(len=:), allocatable, intent(out) :: msg
        character(len=*), intent(in) :: what
        if (.not. allocated(error)) then
            call fatal_error(error, what//" was not refused"); return
        end if
        msg = error%message
        deallocate (error)
    end subroutine refusal

    !> A host array and its device twin with the same random contents
    subroutine twin_real(n1, n2, a, ah, ad, lo, hi)
        integer, intent(in) :: n1, n2
        real(dp), allocatable, target, intent(inout) :: a(:, :)
        type(rarray_t), intent(inout) :: ah, ad
        real(dp), intent(in), optional :: lo, hi
        real(dp) :: l, u
        if (allocated(a)) deallocate (a)
        l = -1.0_dp; u = 1.0_dp
        if (present(lo)) l = lo
        if (present(hi)) u = hi
        allocate (a(n1, n2))
        call random_number(a); a = l + (u - l)*a
        call ah%view(a)
        call ad%create(n1, n2, .true.); call ad%upload(a)
    end subroutine twin_real

    subroutine twin_complex(n1, n2, a, ah, ad)
        integer, intent(in) :: n1, n2
        complex(dp), allocatable, target, intent(inout) :: a(:, :)
        type(carray_t), intent(inout) :: ah, ad
        real(dp) :: re(n1, n2), im(n1, n2)
        call random_number(re); call random_number(im)
        a = cmplx(re - 0.5_dp, im - 0.5_dp, dp)
        call ah%view(a)
        call ad%create(n1, n2, .true.); call ad%upload(a)
    end subroutine twin_complex

    !> |device - host| <= tol max |host| over a real array (the device's read back)
    subroutine same_real(error, ah, ad, what, tol)
        type(error_t), allocatable, intent(inout) :: error
        type(rarray_t), intent(in) :: ah, ad
        character(len=*), intent(in) :: what
        real(dp), intent(in), optional :: tol
        real(dp), allocatable :: b(:, :)
        real(dp) :: t, d
        if (allocated(error)) return
        t = pass_tol; if (present(tol)) t = tol
        allocate (b(ad%n1, ad%n2))
        call ad%download(b)
        d = maxval(abs(b - ah%h))/max(maxval(abs(ah%h)), tiny(1.0_dp))
        call check(error, d <= t, what//": device and CPU differ by "//real_text(d))
    end subroutine same_real

    subroutine same_complex(error, ah, ad, what)
        type(error_t), allocatable, intent(inout) :: error
        type(carray_t), intent(in) :: ah, ad
        character(len=*), intent(in) :: what
        complex(dp), allocatable :: b(:, :)
        real(dp) :: d
        if (allocated(error)) return
        allocate (b(ad%n1, ad%n2))
        call ad%download(b)
        d = maxval(abs(b - ah%h))/max(maxval(abs(ah%h)), tiny(1.0_dp))
        call check(error, d <= pass_tol, what//": device and CPU differ by "//real_text(d))
    end subroutine same_complex

    !> Partial sums against their CPU twins, relative to the largest
    subroutine same_values(error, a, b, what)
        type(error_t), allocatable, intent(inout) :: error
        real(dp), intent(in) :: a(:), b(:)
        character(len=*), intent(in) :: what
        real(dp) :: d
        if (allocated(error)) return
        d = maxval(abs(a - b))/max(maxval(abs(b)), tiny(1.0_dp))
        call check(error, d <= pass_tol, what//": device and CPU differ by "//real_text(d))
    end subroutine same_values

    function real_text(x) result(t)
        real(dp), intent(in) :: x
        character(len=:), allocatable :: t
        character(len=24) :: b
        write (b, '(es10.3)') x
        t = trim(adjustl(b))
    end function real_text

    subroutine device_errors(error, what)
        type(error_t), allocatable, intent(inout) :: error
        character(len=*), intent(in) :: what
        call device_check(error, what)
    end subroutine device_errors

    ! ---- with a device -----------------------------------------------------------------

    subroutine test_info(error)
        type(error_t), allocatable, intent(out) :: error
        type(device_info_t) :: info
        call device_info(info, error); if (allocated(error)) return
        call report("device: "//info%name, info%memory_bytes)
        call check(error, len(info%name) > 0, "no device name"); if (allocated(error)) return
        if (.not. info%emulated) then
            call check(error, info%memory_bytes > 0.0_dp .and. info%driver_version > 0 .and. &
                       info%runtime_version > 0, "a GPU without memory or versions")
        end if
    end subroutine test_info

    subroutine test_passes_shared(error)
        type(error_t), allocatable, intent(out) :: error
        type(contact_law_t) :: law          ! (the hard wall)
        real(dp), allocatable, target :: a(:, :), b(:, :)
        complex(dp), allocatable, target :: c(:, :), d(:, :)
        type(rarray_t) :: ah, ad, bh, bd
        type(carray_t) :: ch, cd, dh, dd
        real(dp) :: rh(ny), rdv(ny)
        integer(i8) :: n1, n2
        call twin_real(nx, ny, a, ah, ad); call twin_real(nx, ny, b, bh, bd)
        call fill(ah, 0.3_dp); call fill(ad, 0.3_dp); call same_real(error, ah, ad, "fill")
        call twin_real(nx, ny, a, ah, ad)
        call scale(ah, 1.7_dp); call scale(ad, 1.7_dp); call same_real(error, ah, ad, "scale")
        call divide(ah, 1.3_dp); call divide(ad, 1.3_dp); call same_real(error, ah, ad, "divide")
        call subtract(ah, 0.2_dp); call subtract(ad, 0.2_dp); call same_real(error, ah, ad, "subtract")
        call scaled_copy(ah, bh, 2.5_dp); call scaled_copy(ad, bd, 2.5_dp); call same_real(error, ah, ad, "scaled_copy")
        call divided_copy(ah, bh, 2.5_dp); call divided_copy(ad, bd, 2.5_dp)
        call same_real(error, ah, ad, "divided_copy")
        call centre_scale(ah, bh, 0.1_dp, 3.0_dp); call centre_scale(ad, bd, 0.1_dp, 3.0_dp)
        call same_real(error, ah, ad, "centre_scale")
        call centre_divide(ah, bh, 0.1_dp, 3.0_dp); call centre_divide(ad, bd, 0.1_dp, 3.0_dp)
        call same_real(error, ah, ad, "centre_divide")
        call project_and_sum(law, ah, rh); call project_and_sum(law, ad, rdv)
        call same_real(error, ah, ad, "project"); call same_values(error, rdv, rh, "project_and_sum")
        call row_sums(bh, rh); call row_sums(bd, rdv); call same_values(error, rdv, rh, "row_sums")
        n1 = count_below(bh, 0.1_dp); n2 = count_below(bd, 0.1_dp)
        if (.not. allocated(error)) call check(error, n1 == n2 .and. n1 > 0, "count_below")
        call twin_complex(nx/2 + 1, ny, c, ch, cd); call twin_complex(nx/2 + 1, ny, d, dh, dd)
        call complex_scale(ch, 0.7_dp); call complex_scale(cd, 0.7_dp); call same_complex(error, ch, cd, "complex_scale")
        call complex_divide(ch, 0.7_dp); call complex_divide(cd, 0.7_dp)
        call same_complex(error, ch, cd, "complex_divide")
        call complex_add(ch, dh); call complex_add(cd, dd); call same_complex(error, ch, cd, "complex_add")
        call multiply_spectrum(ch, dh, 0.3_dp); call multiply_spectrum(cd, dd, 0.3_dp)
        call same_complex(error, ch, cd, "multiply_spectrum")
        call device_errors(error, "shared passes")
        call ad%destroy(); call bd%destroy(); call cd%destroy(); call dd%destroy()
    end subroutine test_passes_shared

    subroutine test_passes_contact(error)
        type(error_t), allocatable, intent(out) :: error
        type(contact_law_t) :: law          ! (the hard wall)
        real(dp), allocatable, target :: u(:, :), h(:, :), p(:, :), g(:, :)
        complex(dp), allocatable, target :: kd(:, :), m(:, :), k(:, :), rk(:, :)
        type(rarray_t) :: uh, ud, hh, hd, ph, pd, gh, gd
        type(carray_t) :: kdh, kdd, mh, md, kh, kdv, rkh, rkd
        real(dp) :: rh(ny), rdv(ny), r3h(3, ny), r3d(3, ny), gmax(2), mins(4)
        integer(i8) :: nc(2)
        call twin_real(nx, ny, u, uh, ud); call twin_real(nx, ny, h, hh, hd)
        call twin_real(nx, ny, p, ph, pd); call twin_real(nx, ny, g, gh, gd)
        call gap_and_contact_sums(law, uh, hh, 0.1_dp, ph, gh, rh, nc(1), gmax(1))
        call gap_and_contact_sums(law, ud, hd, 0.1_dp, pd, gd, rdv, nc(2), gmax(2))
        call same_real(error, gh, gd, "gap"); call same_values(error, rdv, rh, "contact sums")
        if (.not. allocated(error)) call check(error, nc(1) == nc(2) .and. gmax(1) == gmax(2), "contact count, max g")
        call gap_measures(law, ph, gh, 0.05_dp, r3h, mins(1), mins(2))
        call gap_measures(law, pd, gd, 0.05_dp, r3d, mins(3), mins(4))
        call same_real(error, gh, gd, "gap + d"); call same_values(error, reshape(r3d, [3*ny]), reshape(r3h, [3*ny]), &
                                                                   "gap measures")
        if (.not. allocated(error)) call check(error, all(mins(1:2) == mins(3:4)), "min g, min p")
        ! the resolvent (real part of K_d positive, as a kernel's)
        call twin_complex(nx/2 + 1, ny, kd, kdh, kdd)
        kd = cmplx(abs(real(kd)) + 0.1_dp, aimag(kd), dp); call kdd%upload(kd)
        call twin_complex(nx/2 + 1, ny, m, mh, md)
        call resolvent_multiplier(mh, kdh, 0.8_dp, 3.0_dp, real(nx*ny, dp))
        call resolvent_multiplier(md, kdd, 0.8_dp, 3.0_dp, real(nx*ny, dp))
        call same_complex(error, mh, md, "resolvent multiplier")
        call twin_complex(nx/2 + 1, ny, k, kh, kdv); call twin_complex(nx/2 + 1, ny, rk, rkh, rkd)
        call resolvent_apply(kh, mh, rkh, 0.8_dp, .true., 0.5_dp)
        call resolvent_apply(kdv, md, rkd, 0.8_dp, .true., 0.5_dp)
        call same_complex(error, kh, kdv, "resolvent apply")
        call device_errors(error, "contact passes")
        call ud%destroy(); call hd%destroy(); call pd%destroy(); call gd%destroy()
        call kdd%destroy(); call md%destroy(); call kdv%destroy(); call rkd%destroy()
    end subroutine test_passes_contact

    subroutine test_passes_bccg(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: na = nx/2 + 1
        real(dp), allocatable, target :: x(:, :), p(:, :), v(:, :), ks(:, :), wa2(:, :)
        complex(dp), allocatable, target :: kd(:, :), k(:, :), pk(:, :), hk(:, :)
        integer(int8), allocatable :: acth(:, :)
        type(rarray_t) :: xh, xd, ph, pd, vh, vd, ksh, ksd, wah, wad
        type(carray_t) :: kdh, kdd, kh, kdv, pkh, pkd, hkh, hkd
        type(metric_t) :: mh, md
        type(iarray_t) :: ah, ad
        type(grid_t) :: grid
        real(dp) :: wa(na), wb(ny), r3h(3, ny), r3d(3, ny), r4h(4, ny), r4d(4, ny), rh(ny), rdv(ny), ch(ny), cdv(ny), &
                    gmin(2), clip(ny)
        real(dp) :: pts_h(3, 8), pts_d(3, 8)
        real(dp), parameter :: pts4(3, 4) = reshape([1.0_dp, 1.0_dp, 0.7_dp, real(nx, dp), real(ny, dp), -0.4_dp, &
                                                     5.0_dp, 3.0_dp, 1.1_dp, 17.0_dp, 11.0_dp, 0.25_dp], [3, 4])
        complex(dp), allocatable :: pk0(:, :)
        type(carray_t) :: work_h, work_d
        type(fft2d_t) :: fft
        integer(i8) :: nact(2)
        integer :: ncl(2), kh_, kd_, i
        call new_grid(grid, nx, ny, 1.0_dp, 1.0_dp, error); if (allocated(error)) return
        call twin_real(nx, ny, x, xh, xd); call twin_real(nx, ny, p, ph, pd, lo=-0.2_dp, hi=1.0_dp)
        call twin_real(nx, ny, v, vh, vd)
        call twin_complex(na, ny, kd, kdh, kdd)
        call twin_real(na, ny, ks, ksh, ksd)
        call work_d%create(na + ny, max_points, .true.)
        ! metric, both ways (on the device formed where each pass reads it: its values as formed)
        call metric(mh, kdh, 0.7_dp, modulus=.true.); call metric(md, kdd, 0.7_dp, modulus=.true.)
        call metric_values(mh, ksh); call metric_values(md, ksd)
        call same_real(error, ksh, ksd, "metric |K|")
        kd(1, 1) = (0.0_dp, 0.3_dp); kd(3, 2) = (-1.0_dp, 0.2_dp); call kdd%upload(kd)   ! M = 0, M < 0
        call metric(mh, kdh, 0.7_dp, modulus=.false.); call metric(md, kdd, 0.7_dp, modulus=.false.)
        call metric_values(mh, ksh); call metric_values(md, ksd)
        call same_real(error, ksh, ksd, "metric Re K")
        call ah%create(nx, ny, .false.); call ad%create(nx, ny, .true.)
        call set_contact(ah, ph); call set_contact(ad, pd)
        wa = [(merge(1.0_dp, 2.0_dp, i == 1 .or. i == na), i=1, na)]; wb = 1.0_dp
        allocate (wa2(na, 1)); wa2(:, 1) = wa
        call wah%view(wa2); call wad%create(na, 1, .true.); call wad%upload(wa2)
        call statistics(xh, ah, ph, 0.1_dp, r3h, nact(1), gmin(1))
        call statistics(xd, ad, pd, 0.1_dp, r3d, nact(2), gmin(2))
        call same_values(error, reshape(r3d, [3*ny]), reshape(r3h, [3*ny]), "statistics")
        if (.not. allocated(error)) call check(error, nact(1) == nact(2) .and. gmin(1) == gmin(2), "set size, min g")
        call residual(xh, ah, vh, 0.05_dp, r4h); call residual(xd, ad, vd, 0.05_dp, r4d)
        call same_real(error, xh, xd, "residual")
        call same_values(error, reshape(r4d, [4*ny]), reshape(r4h, [4*ny]), "residual sums")
        call set_sum(xh, ah, rh); call set_sum(xd, ad, rdv)
        call same_values(error, rdv, rh, "set_sum")
        call twin_complex(na, ny, k, kh, kdv)
        call precondition(kh, mh, wa, wah, wb, 1.0e3_dp, ch); call precondition(kdv, md, wa, wad, wb, 1.0e3_dp, cdv)
        call same_complex(error, kh, kdv, "precondition"); call same_values(error, cdv, ch, "precondition r.z")
        call direction(xh, ah, vh, 0.4_dp, 0.03_dp); call direction(xd, ad, vd, 0.4_dp, 0.03_dp)
        call same_real(error, xh, xd, "direction x"); call same_real(error, vh, vd, "direction v")
        call energy(kh, mh, wa, wah, wb, ch); call energy(kdv, md, wa, wad, wb, cdv)
        call same_values(error, cdv, ch, "energy")
        call step(xh, ah, ph, vh, 1.1_dp, 0.9_dp, rh, ncl(1), clip)
        call step(xd, ad, pd, vd, 1.1_dp, 0.9_dp, rdv, ncl(2), clip)
        call same_real(error, ph, pd, "step p"); call same_real(error, xh, xd, "step clipped")
        call same_values(error, rdv, rh, "step sum p")
        if (.not. allocated(error)) call check(error, ncl(1) == ncl(2) .and. ncl(1) > 0, "points clipped")
        call clipped_points(xh, clip, 0, 8, pts_h, kh_); call clipped_points(xd, clip, 0, 8, pts_d, kd_)
        if (.not. allocated(error)) call check(error, kh_ == kd_ .and. all(pts_h(:, 1:kh_) == pts_d(:, 1:kd_)), &
                                               "clipped points")
        call twin_complex(na, ny, pk, pkh, pkd); call twin_complex(na, ny, hk, hkh, hkd)
        call update_transform(pkh, kh, 1.2_dp, 0.3_dp); call update_transform(pkd, kdv, 1.2_dp, 0.3_dp)
        call same_complex(error, pkh, pkd, "update_transform")
        call step_transform(pkh, kh, mh, hkh, 1.2_dp, 0.3_dp, 0.8_dp)
        call step_transform(pkd, kdv, md, hkd, 1.2_dp, 0.3_dp, 0.8_dp)
        call same_complex(error, pkh, pkd, "step_transform p^"); call same_complex(error, kh, kdv, "step_transform gap")
        call gap_multiply(kh, pkh, mh, hkh, 0.6_dp); call gap_multiply(kdv, pkd, md, hkd, 0.6_dp)
        call same_complex(error, kh, kdv, "gap_multiply")
        ! a few points' transforms (the origin, the far corner, two inside; on the device their
        ! factors formed there), against FFTW's transform of the field that holds them
        call twin_complex(na, ny, pk, pkh, pkd)
        pk0 = pk
        call add_points(pkh, pts4, grid, work_h); call add_points(pkd, pts4, grid, work_d)
        call same_complex(error, pkh, pkd, "add_points")
        call fft%init(nx, ny, error, planner='estimate'); if (allocated(error)) return
        fft%x = 0.0_dp
        do i = 1, size(pts4, 2)
            fft%x(nint(pts4(1, i)), nint(pts4(2, i))) = pts4(3, i)
        end do
        call fft%forward()
        if (.not. allocated(error)) call check(error, maxval(abs(pk - pk0 - fft%k)) <= pass_tol*maxval(abs(fft%k)), &
                                               "add_points: not the transform of the points")
        call fft%destroy(); call work_d%destroy()
        call device_errors(error, "bccg passes")
        call xd%destroy(); call pd%destroy(); call vd%destroy(); call ksd%destroy(); call wad%destroy()
        call kdd%destroy(); call kdv%destroy(); call pkd%destroy(); call hkd%destroy(); call ad%destroy()
        call ah%destroy(); call mh%destroy(); call md%destroy()
    end subroutine test_passes_bccg

    subroutine test_passes_pdr(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: na = nx/2 + 1
        real(dp), allocatable, target :: x(:, :), h(:, :), p(:, :), z(:, :)
        complex(dp), allocatable, target :: kd(:, :), k(:, :), hk(:, :), cm(:, :), pk(:, :)
        type(rarray_t) :: xh, xd, hh, hd, ph, pd, zh, zd
        type(carray_t) :: kdh, kdd, kh, kdv, hkh, hkd, cmh, cmd, pkh, pkd
        type(metric_t) :: mh, md
        real(dp) :: rh(ny), rdv(ny), r2h(2, ny), r2d(2, ny), gmin(2)
        integer(i8) :: nc(2)
        call twin_real(nx, ny, x, xh, xd); call twin_real(nx, ny, h, hh, hd)
        call twin_real(nx, ny, p, ph, pd, lo=-0.3_dp, hi=1.0_dp); call twin_real(nx, ny, z, zh, zd)
        call twin_complex(na, ny, kd, kdh, kdd)
        kd = cmplx(abs(real(kd)) + 0.1_dp, aimag(kd), dp); kd(1, 1) = (0.0_dp, 0.0_dp)   ! (M = 0 there)
        call kdd%upload(kd)
        call metric(mh, kdh, 0.7_dp, modulus=.true.); call metric(md, kdd, 0.7_dp, modulus=.true.)
        call twin_complex(na, ny, k, kh, kdv); call twin_complex(na, ny, hk, hkh, hkd)
        call twin_complex(na, ny, cm, cmh, cmd); call twin_complex(na, ny, pk, pkh, pkd)
        call step_constant(cmh, kh, mh, kdh, 0.9_dp, 0.4_dp, 37.0_dp)
        call step_constant(cmd, kdv, md, kdd, 0.9_dp, 0.4_dp, 37.0_dp)
        call same_complex(error, cmh, cmd, "step_constant")
        call resolvent(kh, hkh, mh, kdh, cmh, 0.4_dp, 37.0_dp); call resolvent(kdv, hkd, md, kdd, cmd, 0.4_dp, 37.0_dp)
        call same_complex(error, kh, kdv, "resolvent x^"); call same_complex(error, hkh, hkd, "resolvent heights")
        call scaled_product(kh, kdh, pkh, 0.3_dp); call scaled_product(kdv, kdd, pkd, 0.3_dp)
        call same_complex(error, kh, kdv, "scaled_product")
        call full_contact(kh, mh, kdh, 5.0_dp); call full_contact(kdv, md, kdd, 5.0_dp)
        call same_complex(error, kh, kdv, "full_contact")
        call gap_to_z(kh, mh, 0.9_dp, 37.0_dp); call gap_to_z(kdv, md, 0.9_dp, 37.0_dp)
        call same_complex(error, kh, kdv, "gap_to_z")
        call residual_sums(xh, hh, 0.1_dp, 2.0_dp, ph, rh, nc(1)); call residual_sums(xd, hd, 0.1_dp, 2.0_dp, pd, rdv, nc(2))
        call same_values(error, rdv, rh, "residual_sums")
        if (.not. allocated(error)) call check(error, nc(1) == nc(2), "contact count")
        call residual_gap(xh, hh, 0.1_dp, 2.0_dp, 0.3_dp, ph, r2h, gmin(1))
        call residual_gap(xd, hd, 0.1_dp, 2.0_dp, 0.3_dp, pd, r2d, gmin(2))
        call same_values(error, reshape(r2d, [2*ny]), reshape(r2h, [2*ny]), "residual_gap")
        if (.not. allocated(error)) call check(error, gmin(1) == gmin(2), "min g")
        call relax(zh, ph, xh, 1.5_dp); call relax(zd, pd, xd, 1.5_dp); call same_real(error, zh, zd, "relax")
        call add_scaled(zh, xh, -1.5_dp); call add_scaled(zd, xd, -1.5_dp); call same_real(error, zh, zd, "add_scaled")
        call sum_of(zh, ph, xh); call sum_of(zd, pd, xd); call same_real(error, zh, zd, "sum_of")
        call one_plus(zh, xh); call one_plus(zd, xd); call same_real(error, zh, zd, "one_plus")
        call difference_from(zh, ph); call difference_from(zd, pd); call same_real(error, zh, zd, "difference_from")
        call device_errors(error, "pdr passes")
        call xd%destroy(); call hd%destroy(); call pd%destroy(); call zd%destroy(); call md%destroy(); call mh%destroy()
        call kdd%destroy(); call kdv%destroy(); call hkd%destroy(); call cmd%destroy(); call pkd%destroy()
    end subroutine test_passes_pdr

    subroutine test_passes_dr(error)
        type(error_t), allocatable, intent(out) :: error
        type(contact_law_t) :: law          ! (the hard wall)
        integer, parameter :: m = 3
        real(dp), allocatable, target :: x(:, :), z(:, :), zp(:, :), fp(:, :), p(:, :), g(:, :)
        type(rarray_t) :: xh, xd, zh, zd, zph, zpd, fph, fpd, ph, pd, gh, gd
        type(sarray_t) :: dfh, dfd, gmh, gmd
        real(dp) :: rows_h(1 + 2*m, ny), rows_d(1 + 2*m, ny), rp(2), rg(2), coef(m), load_h(2, ny), load_d(2, ny), &
                    vmax(2)
        real(real32), allocatable :: hist(:, :)
        integer :: mk
        call twin_real(nx, ny, x, xh, xd); call twin_real(nx, ny, z, zh, zd)
        call twin_real(nx, ny, zp, zph, zpd); call twin_real(nx, ny, fp, fph, fpd)
        call twin_real(nx, ny, p, ph, pd); call twin_real(nx, ny, g, gh, gd)
        call dfh%create(nx*ny, m, .false.); call gmh%create(nx*ny, m, .false.)
        call dfd%create(nx*ny, m, .true.); call gmd%create(nx*ny, m, .true.)
        allocate (hist(nx*ny, m)); call random_number(hist)
        dfh%h = hist; gmh%h = hist
        call upload_single(dfd, hist); call upload_single(gmd, hist)
        ! Anderson's passes, the residual reflected from x (dr) and given (pdr's mixing: g as f)
        do mk = 0, m
            call anderson_columns(xh, zh, dfh, gmh, zph, fph, max(mk, 1), mk, rows_h, rp(1), rg(1), law)
            call anderson_columns(xd, zd, dfd, gmd, zpd, fpd, max(mk, 1), mk, rows_d, rp(2), rg(2), law)
            call same_values(error, reshape(rows_d(1:1 + 2*mk, :), [(1 + 2*mk)*ny]), &
                             reshape(rows_h(1:1 + 2*mk, :), [(1 + 2*mk)*ny]), "Anderson columns, reflected")
            if (.not. allocated(error)) call check(error, rp(1) == rp(2) .and. rg(1) == rg(2), "dr map rp, rg")
            call same_history(dfh, dfd, "dF"); call same_history(gmh, gmd, "G")
            call anderson_columns(gh, zh, dfh, gmh, zph, fph, max(mk, 1), mk, rows_h, rp(1), rg(1))
            call anderson_columns(gd, zd, dfd, gmd, zpd, fpd, max(mk, 1), mk, rows_d, rp(2), rg(2))
            call same_values(error, reshape(rows_d(1:1 + 2*mk, :), [(1 + 2*mk)*ny]), &
                             reshape(rows_h(1:1 + 2*mk, :), [(1 + 2*mk)*ny]), "Anderson columns, given")
            call same_history(dfh, dfd, "dF"); call same_history(gmh, gmd, "G")
        end do
        coef = [0.3_dp, -0.2_dp, 0.1_dp]
        call anderson_update(xh, zh, gmh, zph, fph, coef, m, law)
        call anderson_update(xd, zd, gmd, zpd, fpd, coef, m, law)
        call same_real(error, zh, zd, "Anderson update z"); call same_real(error, fph, fpd, "Anderson update f")
        call same_real(error, xh, xd, "Anderson update x")
        call anderson_update(gh, zh, gmh, zph, fph, coef, m)
        call anderson_update(gd, zd, gmd, zpd, fpd, coef, m)
        call same_real(error, zh, zd, "Anderson update z, given f")
        call dr_rebalance(law, xh, zh, 3.0_dp); call dr_rebalance(law, xd, zd, 3.0_dp)
        call same_real(error, zh, zd, "rebalance")
        call dr_project(law, ph, xh, zh, 2.0_dp); call dr_project(law, pd, xd, zd, 2.0_dp)
        call same_real(error, ph, pd, "project")
        call dr_restore(xh, zh, zph, fph); call dr_restore(xd, zd, zpd, fpd); call same_real(error, xh, xd, "restore")
        call dr_add_gap(zh, gh, 0.7_dp, 3.0_dp); call dr_add_gap(zd, gd, 0.7_dp, 3.0_dp)
        call same_real(error, zh, zd, "add_gap")
        call dr_load_sums(law, xh, zh, 0.2_dp, load_h, vmax(1)); call dr_load_sums(law, xd, zd, 0.2_dp, load_d, vmax(2))
        call same_values(error, reshape(load_d, [2*ny]), reshape(load_h, [2*ny]), "load_sums")
        if (.not. allocated(error)) call check(error, vmax(1) == vmax(2), "load_sums: max v")
        call dr_shift(zh, -0.3_dp); call dr_shift(zd, -0.3_dp); call same_real(error, zh, zd, "shift")
        call device_errors(error, "dr passes")
        call xd%destroy(); call zd%destroy(); call zpd%destroy(); call fpd%destroy(); call pd%destroy(); call gd%destroy()
        call dfd%destroy(); call gmd%destroy(); call dfh%destroy(); call gmh%destroy()
    contains
        subroutine upload_single(a, v)
            use veslide_device, only: device_upload
            type(sarray_t), intent(inout) :: a
            real(real32), intent(in) :: v(:, :)
            call device_upload(a%d, v, 4_i8*size(v))
        end subroutine upload_single
        subroutine same_history(ah, ad, what)
            use veslide_device, only: device_download
            type(sarray_t), intent(in) :: ah, ad
            character(len=*), intent(in) :: what
            real(real32) :: b(ad%n1, ad%n2)
            if (allocated(error)) return
            call device_download(b, ad%d, 4_i8*size(b))
            call check(error, all(b == ah%h), "dr history "//what//" differs")
        end subroutine same_history
    end subroutine test_passes_dr

    !> cuFFT (or the emulated device's FFTW 2-D) against veslide's FFTW blocks, both ways
    subroutine test_transform(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: sizes(2, 3) = reshape([64, 64, 96, 40, 128, 1], [2, 3])
        type(fft2d_t), target :: fft
        type(transform_t) :: t
        real(dp), allocatable :: x(:, :), xb(:, :)
        complex(dp), allocatable :: k(:, :)
        real(dp) :: d
        integer :: c, n1, n2
        do c = 1, size(sizes, 2)
            n1 = sizes(1, c); n2 = sizes(2, c)
            call fft%init(n1, n2, error, planner='estimate'); if (allocated(error)) return
            call t%on_device(n1, n2, error); if (allocated(error)) return
            allocate (x(n1, n2), xb(n1, n2), k(n1/2 + 1, n2))
            call random_number(x)
            fft%x = x; call fft%forward()
            call t%x%upload(x); call t%forward(); call t%k%download(k)
            d = maxval(abs(k - fft%k))/maxval(abs(fft%k))
            call report("forward, relative", d)
            call check(error, d <= 1.0e-14_dp, "forward transform differs from FFTW"); if (allocated(error)) return
            call t%backward_unscaled(); call t%x%download(xb)
            d = maxval(abs(xb/(n1*n2) - x))/maxval(abs(x))
            call check(error, d <= 1.0e-14_dp, "backward(forward(x)) /= x"); if (allocated(error)) return
            call device_errors(error, "transform"); if (allocated(error)) return
            call t%destroy(); call fft%destroy()
            deallocate (x, xb, k)
        end do
    end subroutine test_transform

    subroutine test_dense_bccg(error)
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        real(dp) :: h(16, 16)
        call paper_rough(16, h, error); if (allocated(error)) return
        call new_elastic(m, 1.0e7_dp, 0.5_dp, error); if (allocated(error)) return
        call dense_compare(h, m, [0.0_dp, 0.0_dp], 5.0e4_dp, error, method='bccg', device='gpu')
    end subroutine test_dense_bccg

    subroutine test_dense_pdr(error)
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        real(dp) :: h(32, 32)
        call paper_rough(32, h, error); if (allocated(error)) return
        call paper_solid(100.0_dp, m, error); if (allocated(error)) return
        call dense_compare(h, m, [peak_speed(100.0_dp, 4.0_dp), 0.0_dp], 1.0e5_dp, error, method='pdr', device='gpu')
    end subroutine test_dense_pdr

    subroutine test_dense_dr(error)
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        real(dp) :: h(16, 16)
        call paper_rough(16, h, error); if (allocated(error)) return
        call paper_solid(11.0_dp, m, error); if (allocated(error)) return
        call dense_compare(h, m, [peak_speed(11.0_dp, 2.0_dp), 0.0_dp], 5.0e4_dp, error, method='dr', device='gpu')
    end subroutine test_dense_dr

    !> A one-row profile (ny = 1: the device's 1-D transforms) against the CPU
    subroutine test_profile(error)
        type(error_t), allocatable, intent(out) :: error
        type(contact_state_t) :: sc, sg
        real(dp) :: h(256, 1)
        integer :: i
        h(:, 1) = [(1.0e-5_dp*(cos(6.283185307179586_dp*i/256) + 0.3_dp*sin(6.283185307179586_dp*5*i/256)), i=1, 256)]
        call solve_case(h, 0.01_dp, 0.01_dp/256, 3.0e4_dp, sc, error, device='cpu'); if (allocated(error)) return
        call solve_case(h, 0.01_dp, 0.01_dp/256, 3.0e4_dp, sg, error, device='gpu'); if (allocated(error)) return
        call check(error, sg%device == 'gpu', "not solved on the device"); if (allocated(error)) return
        call check(error, maxval(abs(sg%p - sc%p)) <= 1.0e-10_dp*maxval(sc%p), "profile: device and CPU differ")
    end subroutine test_profile

    !> Every hard case at 32^2 (64^2 on a GPU) converges on the device, friction with its sign
    subroutine test_hard(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(case_t) :: c
        character(len=:), allocatable :: name
        integer :: k, n, pairs
        n = merge(32, 64, device_emulated())
        pairs = 0
        do k = 1, hard_case_count()
            call hard_case(k, n, cfg, name, error); if (allocated(error)) return
            cfg%solver%device = 'gpu'
            call run_case(cfg, c, error)
            if (allocated(error)) then
                error%message = name//": "//error%message; return
            end if
            call check(error, c%state%device == 'gpu', name//": not on the device"); if (allocated(error)) return
            call check(error, c%state%converged, name//": not converged"); if (allocated(error)) return
            call check_friction_sign(cfg, c, name, error); if (allocated(error)) return
            pairs = pairs + c%state%operator_applications
        end do
        call report("FFT pairs over the hard cases", real(pairs, dp))
    end subroutine test_hard

    !> The same cases on the device and the CPU: pressure, area, friction and lateral force to
    !> 1e-10 relative (tolerance 1e-12: both solutions within it of the exact one), FFT pairs
    !> within 2 % (the iteration's path depends on round-off only near its decisions)
    subroutine test_against_cpu(error)
        type(error_t), allocatable, intent(out) :: error
        ! at rest (bccg), near the loss peak (pdr, dr, and pdr with Anderson mixing), ratio 1000 at
        ! speed, anisotropic at 45 deg
        integer, parameter :: cases(6) = [1, 4, 4, 4, 17, 27]
        character(len=4), parameter :: methods(6) = [character(len=4) :: 'auto', 'pdr', 'dr', 'pdr', 'auto', 'pdr']
        integer, parameter :: memories(6) = [-1, -1, -1, 3, -1, -1]
        type(config_t) :: cfg
        type(case_t) :: cc, cg
        character(len=:), allocatable :: name
        real(dp) :: dpres, df(2), da
        integer :: i, n
        n = merge(32, 128, device_emulated())
        do i = 1, size(cases)
            call hard_case(cases(i), n, cfg, name, error); if (allocated(error)) return
            name = name//" ("//trim(methods(i))//trim(merge(", mixing 3", "          ", memories(i) > 0))//")"
            cfg%solver%tolerance = 1.0e-12_dp; cfg%solver%method = trim(methods(i))
            cfg%solver%anderson_memory = memories(i)
            cfg%solver%device = 'cpu'
            call run_case(cfg, cc, error); if (allocated(error)) return
            cfg%solver%device = 'gpu'
            call run_case(cfg, cg, error); if (allocated(error)) return
            dpres = maxval(abs(cg%state%p - cc%state%p))/maxval(cc%state%p)
            da = abs(contact_area_fraction(cg%state%p) - contact_area_fraction(cc%state%p))
            df = abs(cg%force_pa - cc%force_pa)/max(norm2(cc%force_pa), tiny(1.0_dp))
            call report(name//": |dp|/max p", dpres)
            call report(name//": FFT pairs, device - CPU", real(cg%state%operator_applications - &
                                                               cc%state%operator_applications, dp))
            call check(error, cg%state%device == 'gpu' .and. cc%state%device == 'cpu', name//": where solved")
            if (allocated(error)) return
            call check(error, dpres <= 1.0e-10_dp, name//": pressures differ by "//real_text(dpres))
            if (allocated(error)) return
            call check(error, da <= 1.0e-10_dp, name//": contact areas differ"); if (allocated(error)) return
            call check(error, all(df <= 1.0e-10_dp), name//": forces differ by "//real_text(maxval(df)))
            if (allocated(error)) return
            call check(error, abs(cg%state%operator_applications - cc%state%operator_applications) <= &
                       max(2, nint(0.02_dp*cc%state%operator_applications)), name//": FFT pairs differ")
            if (allocated(error)) return
        end do
    end subroutine test_against_cpu

    !> The passes of the adhesive laws' solver (gcg) against their CPU twins on random data: a gap
    !> with closed cells and cells at Dugdale's zone edge, both laws, every spectral multiplier and
    !> combination; the int8 sets they make equal
    subroutine test_passes_gcg(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: na = nx/2 + 1
        integer, parameter :: laws(2) = [LAW_EXPONENTIAL, LAW_DUGDALE]
        real(dp), parameter :: s0 = 0.7_dp, rho = 0.25_dp, lam = 0.05_dp
        real(dp), allocatable, target :: g(:, :), r(:, :), at(:, :), pz(:, :), t(:, :), ai(:, :), w(:, :)
        complex(dp), allocatable, target :: k(:, :), ki(:, :)
        type(rarray_t) :: gh, gd, rh, rd, ath, atd, pzh, pzd, th, tdv, aih, aid, wh, wd
        type(carray_t) :: kh, kdv, kih, kid
        type(iarray_t) :: fh, fd, eh, ed
        real(dp) :: r4h(4, ny), r4d(4, ny), e(4)
        integer :: il, mode
        integer(c_int) :: m
        call twin_real(nx, ny, r, rh, rd)
        call twin_real(nx, ny, at, ath, atd)
        call fh%create(nx, ny, .false.); call fd%create(nx, ny, .true.)
        call eh%create(nx, ny, .false.); call ed%create(nx, ny, .true.)
        do il = 1, size(laws)
            call gap_twin()
            call gcg_attract(laws(il), s0, rho, gh, rh, ath, eh, r4h(1:3, :))
            call gcg_attract(laws(il), s0, rho, gd, rd, atd, ed, r4d(1:3, :))
            call same_real(error, ath, atd, "attract"); call same_sums(r4h(1:3, :), r4d(1:3, :), "attract sums")
            call same_set(eh, ed, "Dugdale's edge")
            call gcg_free_set(gh, rh, ath, fh, eh, lam, s0, il == 2, r4h(1:2, :))
            call gcg_free_set(gd, rd, atd, fd, ed, lam, s0, il == 2, r4d(1:2, :))
            call same_real(error, ath, atd, "free set: at"); call same_sums(r4h(1:2, :), r4d(1:2, :), "free set sums")
            call same_set(fh, fd, "free set")
            call gcg_centre(gh, ath, fh, eh, lam, e(1)); call gcg_centre(gd, atd, fd, ed, lam, e(2))
            call same_real(error, ath, atd, "centre")
            ! (to round-off: the exponential law's exp is glibc's vector one on the CPU, as before)
            if (.not. allocated(error)) call check(error, abs(e(1) - e(2)) <= pass_tol*e(1) .and. e(1) > 0.0_dp, &
                                                   "centre: violation "// &
                                                   real_text(e(1))//" on the CPU, "//real_text(e(2))//" on the device")
            if (allocated(error)) return
        end do
        ! the directions' passes
        call twin_real(nx, ny, pz, pzh, pzd); call twin_real(nx, ny, t, th, tdv)
        call gcg_mask(pzh, fh, r4h(1:2, :)); call gcg_mask(pzd, fd, r4d(1:2, :))
        call same_real(error, pzh, pzd, "mask"); call same_sums(r4h(1:2, :), r4d(1:2, :), "mask sums")
        call gcg_shift_dot(pzh, ath, fh, 0.03_dp, r4h(1:1, :)); call gcg_shift_dot(pzd, atd, fd, 0.03_dp, r4d(1:1, :))
        call same_real(error, pzh, pzd, "shift_dot"); call same_sums(r4h(1:1, :), r4d(1:1, :), "shift_dot sums")
        call gcg_dot(ath, pzh, r4h(1:1, :)); call gcg_dot(atd, pzd, r4d(1:1, :))
        call same_sums(r4h(1:1, :), r4d(1:1, :), "dot")
        call gcg_direction(pzh, ath, th, fh, 0.6_dp, r4h(1:1, :))
        call gcg_direction(pzd, atd, tdv, fd, 0.6_dp, r4d(1:1, :))
        call same_real(error, th, tdv, "direction"); call same_sums(r4h(1:1, :), r4d(1:1, :), "direction sums")
        call gcg_curvature(pzh, th, fh, r4h); call gcg_curvature(pzd, tdv, fd, r4d)
        call same_sums(r4h, r4d, "curvature")
        ! steps: Dugdale's stop at the zone's edge, and the smooth law's
        do il = 1, size(laws)
            call gap_twin()
            call twin_real(nx, ny, t, th, tdv)
            e(3) = real(count(g - 0.4_dp*t < 0.0_dp), dp)
            call gcg_step(laws(il), rho, gh, th, 0.4_dp, eh, r4h(1:2, :), e(1))
            call gcg_step(laws(il), rho, gd, tdv, 0.4_dp, ed, r4d(1:2, :), e(2))
            call same_real(error, gh, gd, "step"); call same_sums(r4h(1:2, :), r4d(1:2, :), "step: cells stopped, clipped")
            if (il == 2) call same_set(eh, ed, "step: the cells stopped")
            if (.not. allocated(error)) call check(error, e(1) == e(2) .and. e(1) < 0.0_dp .and. &
                                                   (il == 1 .or. sum(r4h(1, :)) > 0.0_dp) .and. &
                                                   sum(r4h(2, :)) == e(3) .and. e(3) > 0.0_dp, &
                                                   "step: least gap, stops, clipped cells")
            if (allocated(error)) return
        end do
        call gcg_shift_open(gh, -0.1_dp, e(1)); call gcg_shift_open(gd, -0.1_dp, e(2))
        call same_real(error, gh, gd, "shift_open")
        if (.not. allocated(error)) call check(error, e(1) == e(2) .and. e(1) < 0.0_dp, "shift_open: least gap")
        if (allocated(error)) return
        call gcg_gap_sums(gh, .false., r4h(1:2, :)); call gcg_gap_sums(gd, .false., r4d(1:2, :))
        call same_sums(r4h(1:2, :), r4d(1:2, :), "gap sums")
        call gcg_gap_sums(gh, .true., r4h(1:2, :)); call gcg_gap_sums(gd, .true., r4d(1:2, :))
        call same_real(error, gh, gd, "clip"); call same_sums(r4h(1:2, :), r4d(1:2, :), "gap sums, clipped")
        call gcg_extremes(rh, e(1), e(2)); call gcg_extremes(rd, e(3), e(4))
        if (.not. allocated(error)) call check(error, all(e(1:2) == e(3:4)) .and. e(1) < e(2), "extremes")
        if (allocated(error)) return
        ! the combinations
        call twin_real(nx, ny, w, wh, wd)
        do mode = 0, 7
            m = int(mode, c_int)
            call gcg_combine(m, wh, rh, th, 0.3_dp, 1.7_dp, -0.2_dp)
            call gcg_combine(m, wd, rd, tdv, 0.3_dp, 1.7_dp, -0.2_dp)
            call same_real(error, wh, wd, "combine "//str(mode))
        end do
        ! the spectral multipliers (some modes zero, as the mean mode is)
        call twin_real(na, ny, ai, aih, aid, lo=0.1_dp, hi=2.0_dp)
        ai(1, 1) = 0.0_dp; ai(3, 2) = 0.0_dp; call aid%upload(ai)
        call twin_complex(na, ny, ki, kih, kid)
        ki(1, 1) = (0.0_dp, 0.0_dp); ki(4, 3) = (0.0_dp, 0.0_dp); call kid%upload(ki)
        do mode = 0, 4
            m = int(mode, c_int)
            call twin_complex(na, ny, k, kh, kdv)
            call gcg_spectral(m, kh, aih, kih, 0.8_dp, real(nx*ny, dp))
            call gcg_spectral(m, kdv, aid, kid, 0.8_dp, real(nx*ny, dp))
            call same_complex(error, kh, kdv, "spectral "//str(mode))
            call kdv%destroy()
        end do
        call device_errors(error, "gcg passes")
        call gd%destroy(); call rd%destroy(); call atd%destroy(); call pzd%destroy(); call tdv%destroy()
        call aid%destroy(); call kid%destroy(); call wd%destroy(); call fd%destroy(); call ed%destroy()
    contains
        !> g >= 0 with closed cells (about a third) and cells at rho (every seventh)
        subroutine gap_twin()
            integer :: i
            call twin_real(nx, ny, g, gh, gd)
            g = max(g, 0.0_dp)
            do i = 1, nx*ny, 7
                g(mod(i - 1, nx) + 1, (i - 1)/nx + 1) = rho
            end do
            call gd%upload(g)
        end subroutine gap_twin
        subroutine same_sums(a, b, what)
            real(dp), intent(in) :: a(:, :), b(:, :)
            character(len=*), intent(in) :: what
            call same_values(error, reshape(b, [size(b)]), reshape(a, [size(a)]), what)
        end subroutine same_sums
        !> the same set on both (with cells in and out of it; the exponential law's edge empty)
        subroutine same_set(h, d, what)
            type(iarray_t), intent(in) :: h, d
            character(len=*), intent(in) :: what
            integer(int8) :: b(nx, ny)
            logical :: empty
            if (allocated(error)) return
            call device_download(b, d%d, int(nx*ny, i8))
            empty = what == "Dugdale's edge" .and. il == 1
            call check(error, all(b == h%h) .and. (any(b == 1) .neqv. empty) .and. any(b == 0), &
                       what//": device and CPU sets differ (or one is empty or full)")
        end subroutine same_set
    end subroutine test_passes_gcg

    !> The adhesive laws' solver on the device against the CPU: the hard scenes with the hard
    !> groups' exponential law (largest attraction twice the load; test_veslide_hard) at rest
    !> (the conjugate gradients) and in motion (their splitting), with Dugdale's law, under
    !> approach control, and in motion on 128^2, where the splitting's inner steps keep their
    !> conjugacy through a few clipped cells (on both, docs/adhesion.md): converged on both, the
    !> same closed cells, FFT pairs within 2 %, the pressure and the forces to 1e-10
    subroutine test_adhesive_against_cpu(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: cases(6) = [1, 4, 27, 1, 4, 4]
        character(len=11), parameter :: laws(6) = [character(len=11) :: 'exponential', 'exponential', 'exponential', &
                                                   'dugdale', 'exponential', 'exponential']
        type(config_t) :: cfg
        type(case_t) :: cc, cg
        character(len=:), allocatable :: name
        real(dp) :: dpres, df(2)
        integer :: i, n
        n = merge(32, 64, device_emulated())
        do i = 1, size(cases)
            call hard_case(cases(i), merge(128, n, i == 6), cfg, name, error); if (allocated(error)) return
            call with_adhesion(cfg, 2.0_dp, name, error); if (allocated(error)) return
            cfg%adhesion%law = laws(i)
            if (i == 6) name = name//", 128^2"
            if (i == 5) then
                cfg%load%approach_m = 2.0e-6_dp
                name = name//", approach control"
            end if
            name = name//" ("//trim(laws(i))//")"
            cfg%solver%device = 'cpu'
            call run_case(cfg, cc, error); if (allocated(error)) return
            cfg%solver%device = 'gpu'
            call run_case(cfg, cg, error); if (allocated(error)) return
            ! (the law's contact is the closed cells, compared below; p > 0 is not: on open cells
            ! far from contact p = -sigma(g) is 0 to round-off)
            dpres = maxval(abs(cg%state%p - cc%state%p))/maxval(abs(cc%state%p))
            df = abs(cg%force_pa - cc%force_pa)/max(norm2(cc%force_pa), tiny(1.0_dp))
            call report(name//": |dp|/max |p|", dpres)
            call report(name//": FFT pairs (CPU)", real(cc%state%operator_applications, dp))
            call check(error, cg%state%device == 'gpu' .and. cc%state%device == 'cpu', name//": where solved")
            if (allocated(error)) return
            call check(error, cc%state%converged .and. cg%state%converged, name//": not converged")
            if (allocated(error)) return
            call report(name//": iterations, device - CPU", real(cg%state%iterations - cc%state%iterations, dp))
            call report(name//": closed cells that differ", real(count((cg%state%g <= 0.0_dp) .neqv. &
                                                                         (cc%state%g <= 0.0_dp)), dp))
            call check(error, abs(cg%state%operator_applications - cc%state%operator_applications) <= &
                       max(2, nint(0.02_dp*cc%state%operator_applications)), name//": FFT pairs differ")
            if (allocated(error)) return
            call check(error, all((cg%state%g <= 0.0_dp) .eqv. (cc%state%g <= 0.0_dp)), name//": other closed cells")
            if (allocated(error)) return
            call check(error, dpres <= 1.0e-10_dp .and. all(df <= 1.0e-10_dp), &
                       name//": pressures or forces differ by "//real_text(dpres)//", "//real_text(maxval(df)))
            if (allocated(error)) return
            if (i == 6) then
                call report(name//": steps that kept the conjugacy (CPU)", real(cc%state%kept_conjugacy_steps, dp))
                call report(name//": steps that kept the conjugacy (device)", real(cg%state%kept_conjugacy_steps, dp))
                call check(error, cc%state%kept_conjugacy_steps > 0 .and. cg%state%kept_conjugacy_steps > 0, &
                           name//": no step kept the conjugacy through a clipped cell")
                if (allocated(error)) return
            end if
        end do
    end subroutine test_adhesive_against_cpu

    !> The 29 hard scenes with the hard groups' exponential law (test_veslide_hard's
    !> scenes-adhesive-gcg: largest attraction twice the load) on the device and on the CPU: the
    !> same verdict on each; where converged (27 of 29 at 32^2 on the emulated device) the same
    !> closed cells, pressures within 1e-10 of the largest, the friction resisting the motion and
    !> FFT pairs within 5 % (round-off moves the splitting's path: 2.3 % at most measured); where
    !> not, the CPU test's categories alone (Einf/E0 >= 100 in motion, at the iteration cap, the
    !> cohesive zone below a cell and said so; or a load in a jump, said so)
    subroutine test_adhesive_hard(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(case_t) :: cc, cg
        character(len=:), allocatable :: name
        integer :: k, n, converged, pairs
        real(dp) :: dpres, worst, spread
        n = merge(32, 64, device_emulated())
        converged = 0; pairs = 0; worst = 0.0_dp; spread = 0.0_dp
        do k = 1, hard_case_count()
            call hard_case(k, n, cfg, name, error); if (allocated(error)) return
            call with_adhesion(cfg, 2.0_dp, name, error); if (allocated(error)) return
            cfg%solver%device = 'cpu'
            call run_case(cfg, cc, error); if (allocated(error)) return
            cfg%solver%device = 'gpu'
            call run_case(cfg, cg, error); if (allocated(error)) return
            call check(error, cg%state%device == 'gpu', name//": not on the device"); if (allocated(error)) return
            call check(error, cg%state%converged .eqv. cc%state%converged, name//": another verdict on the device")
            if (allocated(error)) return
            if (.not. cg%state%converged) then
                call check(error, has_warning(cg, 'adhesive-load-jump') .or. &
                           (cg%state%iterations >= cfg%solver%max_iterations .and. &
                            cfg%material%ratio >= 100.0_dp .and. &
                            has_warning(cg, 'adhesion-zone-unresolved')), &
                           name//": not converged on the device, and not in the categories the CPU's may not")
                if (allocated(error)) return
                cycle
            end if
            converged = converged + 1
            dpres = maxval(abs(cg%state%p - cc%state%p))/maxval(abs(cc%state%p))
            worst = max(worst, dpres)
            spread = max(spread, abs(real(cg%state%operator_applications - cc%state%operator_applications, dp))/ &
                         cc%state%operator_applications)
            pairs = pairs + cg%state%operator_applications
            call check(error, all((cg%state%g <= 0.0_dp) .eqv. (cc%state%g <= 0.0_dp)) .and. dpres <= 1.0e-10_dp, &
                       name//": other closed cells, or pressures "//real_text(dpres)//" apart")
            if (allocated(error)) return
            call check_friction_sign(cfg, cg, name//" (device)", error); if (allocated(error)) return
            call check(error, abs(cg%state%operator_applications - cc%state%operator_applications) <= &
                       max(2, nint(0.05_dp*cc%state%operator_applications)), name//": FFT pairs differ")
            if (allocated(error)) return
        end do
        call report("converged on both", real(converged, dp))
        call report("their FFT pairs on the device", real(pairs, dp))
        call report("largest |dp|/max |p|, device - CPU", worst)
        call report("largest relative difference of FFT pairs", spread)
    end subroutine test_adhesive_hard

    !> Two solves of the same case on the device give the same bits
    subroutine test_repeat(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(case_t) :: a, b
        character(len=:), allocatable :: name
        integer :: k
        do k = 4, 22, 18        ! ratio 11 near the loss peak; a contact of a fraction of a percent
            call hard_case(k, merge(32, 128, device_emulated()), cfg, name, error); if (allocated(error)) return
            cfg%solver%device = 'gpu'
            call run_case(cfg, a, error); if (allocated(error)) return
            call run_case(cfg, b, error); if (allocated(error)) return
            call check(error, all(a%state%p == b%state%p) .and. all(a%state%g == b%state%g) .and. &
                       a%state%operator_applications == b%state%operator_applications, name//": not bitwise repeatable")
            if (allocated(error)) return
        end do
    end subroutine test_repeat

    !> What the device does not run is refused by name with 'gpu', and solved on the CPU by 'auto';
    !> a case is refused before it is built in the words of the solve (the solver table's)
    subroutine test_refusals(error)
        type(error_t), allocatable, intent(out) :: error
        type(contact_state_t) :: s
        type(config_t) :: cfg
        type(case_t) :: c
        real(dp) :: h(16, 16)
        character(len=:), allocatable :: msg, before, name
        call paper_rough(16, h, error); if (allocated(error)) return
        call solve_case(h, 0.01_dp, 0.01_dp, 1.0e5_dp, s, error, method='pk', device='gpu')
        call refusal(error, msg, "pk on the device"); if (allocated(error)) return
        call check(error, index(msg, "'pk' does not run on the device") > 0, "message: "//msg)
        if (allocated(error)) return
        call solve_case(h, 0.01_dp, 0.01_dp, 1.0e5_dp, s, error, method='pk', device='auto')
        if (allocated(error)) return
        call check(error, s%device == 'cpu', "'auto' with pk did not take the CPU")
        if (allocated(error)) return
        ! the same refusal before the case is built (a solid at rest: pk takes it on the CPU)
        call hard_case(1, 16, cfg, name, error); if (allocated(error)) return
        cfg%solver%method = 'pk'; cfg%solver%device = 'gpu'
        call run_case(cfg, c, error)
        call refusal(error, before, "pk on the device, before the case is built"); if (allocated(error)) return
        call check(error, before(index(before, "&solver method"):) == msg(index(msg, "&solver method"):), &
                   "refused otherwise before the case is built: '"//before//"' and at the solve: '"//msg//"'")
        if (allocated(error)) return
        ! Anderson memory beyond the device passes', before the case is built and at the solve
        cfg%solver%method = 'dr'; cfg%solver%anderson_memory = 9
        call run_case(cfg, c, error)
        call refusal(error, before, "anderson_memory = 9 on the device"); if (allocated(error)) return
        call solve_case(h, 0.01_dp, 0.01_dp, 1.0e5_dp, s, error, method='dr', device='gpu', anderson_memory=9)
        call refusal(error, msg, "anderson_memory = 9 on the device, at the solve"); if (allocated(error)) return
        call check(error, index(msg, "&solver anderson_memory = 9") > 0 .and. before(index(before, "&solver"):) == &
                   msg(index(msg, "&solver"):), "refused otherwise before the case is built: '"//before// &
                   "' and at the solve: '"//msg//"'")
    end subroutine test_refusals

    !> The device memory a solve holds is counted, and all of it is given back
    subroutine test_memory(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(case_t) :: c
        character(len=:), allocatable :: name
        real(dp) :: before, cells
        call hard_case(4, 64, cfg, name, error); if (allocated(error)) return
        cfg%solver%device = 'gpu'; cfg%solver%method = 'pdr'
        before = device_bytes_in_use()
        call device_reset_peak()
        call run_case(cfg, c, error); if (allocated(error)) return
        cells = 64.0_dp**2
        call report("device peak [bytes/cell]", (device_peak_bytes() - before)/cells)
        call check(error, device_peak_bytes() - before > 60.0_dp*cells, "device memory not counted")
        if (allocated(error)) return
        call check(error, device_bytes_in_use() <= before + 1.0e6_dp, "device memory not given back")
    end subroutine test_memory

    !> cuFFT's work area lent by an array the caller does not read across a transform: used when
    !> it is large enough (the emulated device models it as nx ny doubles and writes NaN there at
    !> every transform, as a GPU leaves garbage), the transform's own otherwise
    subroutine test_work_area(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n1 = 32, n2 = 24
        type(transform_t) :: t
        type(rarray_t) :: big, small
        real(dp) :: a(n1, n2), b(n1, n2 - 1), before, start
        start = device_bytes_in_use()
        call t%on_device(n1, n2, error); if (allocated(error)) return
        call big%create(n1, n2, .true.); call small%create(n1, n2 - 1, .true.)
        call random_number(a); call big%upload(a)
        call random_number(b); call small%upload(b)
        call t%x%upload(a)
        before = device_bytes_in_use()
        call t%lend_work(small)
        call check(error, .not. t%lent .and. device_bytes_in_use() == before + t%work_bytes, &
                   "a work area smaller than cuFFT's was taken, or the transform's own not counted")
        if (allocated(error)) return
        call t%lend_work(big)
        call check(error, t%lent .eqv. t%work_bytes > 0.0_dp, "a large enough work area was not taken")
        if (allocated(error)) return
        call t%forward(); call t%backward_unscaled()
        call device_errors(error, "transform with a lent work area"); if (allocated(error)) return
        call small%download(b)
        call check(error, all(b == b), "the transform wrote into an array it no longer holds")
        if (allocated(error)) return
        if (device_emulated()) then
            call big%download(a)
            call check(error, all(a /= a), "the emulated device did not spoil the lent work area")
            if (allocated(error)) return
        end if
        call t%destroy()
        call check(error, device_bytes_in_use() == start + 8.0_dp*n1*n2 + 8.0_dp*n1*(n2 - 1), &
                   "the transform's buffers and own work area not given back")
        call big%destroy(); call small%destroy()
    end subroutine test_work_area

    !> `veslide --memory`'s device estimate (veslide_memory) against the device's own count of what
    !> a solve holds at its peak (every allocation, cuFFT's work area included; on the emulated
    !> device its model, nx ny doubles): bccg, pdr, dr and pdr with mixing in the layout the
    !> device's room gives them (room, on the emulated device, whose free memory is unknown, but
    !> with VESLIDE_DEVICE_LEAN=1), and pdr in its
    !> lean layout, which the refusal's estimate is (the same solution to round-off, and at most a
    !> few FFT pairs apart): per cell at least the estimate's bytes, and no more than
    !> what the estimate leaves out as small: the half-spectra's row beyond nx/2 (at most 6 of
    !> them, 16 ny bytes each: the estimate counts 8 per cell), bccg's few clipped points
    !> transformed directly (at most 8, 16 (nx/2 + 1 + ny) bytes each) and the Hermitian weights
    !> (8 (nx/2 + 1)): 2.3 bytes per cell at 128^2, less than any array of the grid but act's;
    !> and gcg in motion (the adhesive laws' splitting, the most that solver holds)
    subroutine test_memory_estimate(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 128
        integer, parameter :: cases(4) = [1, 4, 4, 4]
        character(len=4), parameter :: methods(4) = [character(len=4) :: 'bccg', 'pdr', 'dr', 'pdr']
        integer, parameter :: memories(4) = [-1, -1, -1, 3]
        !> holds cuFFT's work area of its own (the estimate counts 8 bytes per cell for it, the
        !> most cuFFT takes: it takes none on small grids)
        logical, parameter :: own_work(4) = [.false., .true., .false., .true.]
        type(transform_t) :: t
        type(config_t) :: cfg
        type(case_t) :: c
        type(contact_problem_t) :: problem
        type(contact_state_t) :: lean
        type(solver_options_t) :: opts
        type(fft2d_t) :: fft
        character(len=:), allocatable :: name
        real(dp) :: before, measured, estimate, cells, small, dpres, work
        integer :: i
        logical :: room
        ! (the row partials' buffer, which a solve keeps, grown first by a small one)
        call hard_case(4, 16, cfg, name, error); if (allocated(error)) return
        cfg%solver%device = 'gpu'
        call run_case(cfg, c, error); if (allocated(error)) return
        cells = real(n, dp)**2
        small = (6*16.0_dp*n + 8*16.0_dp*(n/2 + 1 + n) + 8.0_dp*(n/2 + 1))/cells
        call t%on_device(n, n, error); if (allocated(error)) return
        work = t%work_bytes/cells
        call t%destroy()
        room = device_has_room(0.0_dp)      ! (no with VESLIDE_DEVICE_LEAN=1: pdr's lean layout)
        call report("cuFFT's work area [bytes/cell]", work)
        do i = 1, size(cases)
            call hard_case(cases(i), n, cfg, name, error); if (allocated(error)) return
            cfg%solver%device = 'gpu'; cfg%solver%method = trim(methods(i))
            cfg%solver%anderson_memory = memories(i); cfg%solver%tolerance = 1.0e-6_dp
            name = trim(methods(i))//trim(merge(" with mixing 3", "              ", memories(i) > 0))
            before = device_bytes_in_use()
            call device_reset_peak()
            call run_case(cfg, c, error); if (allocated(error)) return
            measured = (device_peak_bytes() - before)/cells
            estimate = device_bytes_per_cell(c%spec, room=room)
            if (own_work(i) .and. (room .or. memories(i) > 0)) estimate = estimate - 8.0_dp + work
            call check(error, c%state%device == 'gpu', name//": not on the device"); if (allocated(error)) return
            call check_estimate(name)
            if (allocated(error)) return
        end do
        ! the last case again, pdr in its lean layout, on the case's kernel and heights
        name = "pdr, lean layout"
        call new_contact_problem(problem, c%kernel, c%h, c%spec%mean_pressure_pa, error); if (allocated(error)) return
        call fft%init(n, n, error, planner='estimate'); if (allocated(error)) return
        opts = c%spec%solver; opts%anderson_memory = -1; opts%device_lean = .true.
        before = device_bytes_in_use()
        call device_reset_peak()
        call solve_contact(problem, fft, opts, lean, error); if (allocated(error)) return
        measured = (device_peak_bytes() - before)/cells
        cfg%solver%anderson_memory = -1
        call run_case(cfg, c, error); if (allocated(error)) return       ! (the same case, room: its layout)
        estimate = device_bytes_per_cell(c%spec)
        call check_estimate(name); if (allocated(error)) return
        dpres = maxval(abs(lean%p - c%state%p))/maxval(c%state%p)
        call report(name//": |dp|/max p against the layout with room", dpres)
        call report(name//": FFT pairs, lean - with room", real(lean%operator_applications - &
                                                                 c%state%operator_applications, dp))
        call check(error, lean%converged .and. lean%device == 'gpu', name//": not converged on the device")
        if (allocated(error)) return
        ! (both within the tolerance 1e-6 of the solution)
        call check(error, dpres <= 1.0e-5_dp, name//": the pressures differ by "//real_text(dpres))
        call fft%destroy()
        if (allocated(error)) return
        ! the adhesive laws' solver in motion (its splitting: the most it holds)
        call hard_case(4, n, cfg, name, error); if (allocated(error)) return
        call with_adhesion(cfg, 2.0_dp, name, error); if (allocated(error)) return
        cfg%solver%device = 'gpu'; cfg%solver%tolerance = 1.0e-6_dp
        name = "gcg"
        before = device_bytes_in_use()
        call device_reset_peak()
        call run_case(cfg, c, error); if (allocated(error)) return
        measured = (device_peak_bytes() - before)/cells
        estimate = device_bytes_per_cell(c%spec)
        call check(error, c%state%device == 'gpu', name//": not on the device"); if (allocated(error)) return
        call check_estimate(name)

    contains

        subroutine check_estimate(what)
            character(len=*), intent(in) :: what
            call report(what//": device peak [bytes/cell]", measured)
            call report(what//": its estimate [bytes/cell]", estimate)
            call check(error, measured >= estimate .and. measured <= estimate + small, what//": the device"// &
                       " held "//real_text(measured)//" bytes per cell, the estimate says "//real_text(estimate))
        end subroutine check_estimate

    end subroutine test_memory_estimate

    !> A study's chain of speeds on the device keeps its fields there from case to case: the next
    !> speed's warm start is formed where the last case's p and g are, and the heights stay, so
    !> that only the first case's heights and start and each case's multiplier go up (dr, which
    !> uploads nothing else: pdr's inner solves also send up the transforms of a few clipped
    !> points); every case converges on the device (the results equal those with the uploads bit
    !> for bit: scripts/same_outputs.py --device gpu, study_speeds and study_pdr)
    subroutine test_study_kept(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 32
        type(config_t) :: cfg
        character(len=:), allocatable :: name, out
        real(dp) :: up0, up, cells, expected, v
        integer :: nfail
        call hard_case(4, n, cfg, name, error); if (allocated(error)) return
        cfg%solver%device = 'gpu'; cfg%solver%method = 'dr'
        v = cfg%motion%speed_m_s
        cfg%sweep%speeds = [v, 1.3_dp*v, 1.7_dp*v]
        cfg%output%fields = .false.
        out = unique_name('device-study.h5')
        up0 = device_moved_bytes(.true.)
        call run_study(cfg, out, nfail, error)
        call remove(out)
        if (allocated(error)) return
        up = device_moved_bytes(.true.) - up0
        cells = real(n, dp)**2
        expected = 2*8*cells + 3*16.0_dp*(n/2 + 1)*n
        call report("uploaded [bytes/cell]", up/cells)
        call report("uploaded with the warm starts sent up [bytes/cell]", (up + 2*3*8*cells)/cells)
        call check(error, nfail == 0, "a case of the study did not converge"); if (allocated(error)) return
        call check(error, up == expected, "uploaded "//real_text(up)//" bytes, expected "//real_text(expected)// &
                   " (the first case's heights and start, each case's multiplier)")
    end subroutine test_study_kept

end module test_veslide_device
