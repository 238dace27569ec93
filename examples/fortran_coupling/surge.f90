! The lines of a scenario stepped from Fortran through moorsim's C API: the vessel surges
! 5 m at a 60 s period and heaves 1 m at 10 s; every 0.1 s the lines are stepped to its new
! pose and velocity. Prints each line's fairlead tension [N] at 60 s, full precision.
!
!   surge SCENARIO.yaml
program surge
  use, intrinsic :: iso_c_binding
  use moorsim
  implicit none
  type(c_ptr) :: lines
  character(len=1024) :: path
  real(c_double) :: x(6), xd(6), f(6), t, dt
  real(c_double), allocatable :: tensions(:)
  real(c_double), parameter :: pi = 4.0d0 * atan(1.0d0)
  real(c_double) :: ws, wh
  integer(c_int) :: count
  integer :: k

  if (command_argument_count() /= 1) then
    write (*, '(a)') 'usage: surge SCENARIO.yaml'
    stop 2
  end if
  call get_command_argument(1, path)
  lines = moorsim_lines_create(trim(path) // c_null_char)
  if (.not. c_associated(lines)) then
    write (*, '(a)') 'surge: ' // moorsim_last_error()
    stop 1
  end if
  if (moorsim_lines_count(lines, count) /= MOORSIM_OK) stop 1
  allocate(tensions(count))

  ws = 2.0d0 * pi / 60.0d0
  wh = 2.0d0 * pi / 10.0d0
  x = 0.0d0
  xd = 0.0d0
  if (moorsim_lines_init(lines, x, xd) /= MOORSIM_OK) then
    write (*, '(a)') 'surge: ' // moorsim_last_error()
    stop 1
  end if
  t = 0.0d0
  do k = 1, 600
    dt = 0.1d0
    x(1) = 5.0d0 * sin(ws * k * 0.1d0)
    xd(1) = 5.0d0 * ws * cos(ws * k * 0.1d0)
    x(3) = sin(wh * k * 0.1d0)
    xd(3) = wh * cos(wh * k * 0.1d0)
    if (moorsim_lines_step(lines, x, xd, f, t, dt) /= MOORSIM_OK) then
      write (*, '(a)') 'surge: ' // moorsim_last_error()
      stop 1
    end if
  end do
  if (moorsim_lines_fairlead_tensions(lines, tensions, count) /= MOORSIM_OK) stop 1
  write (*, '(a, f6.1, a)') 'tensions at ', t, ' s:'
  do k = 1, count
    write (*, '(es25.17)') tensions(k)
  end do
  call moorsim_lines_destroy(lines)
end program surge
